"""The real E-Boat (the default) against the figures the sheet measured on the seed team's CAD
(shared/eboat/README.md, "The real geometry, measured from the CAD"): the hull lofted from the offsets table,
where it floats, the links composed through the URDF's joint chain, the righting arm, the foils and the parts.

References are the sheet's figures (typed in here), hydrostatics of the mesh by waterlines
(``tests.waterlines``: not the divergence theorem of the code under test), the URDF's chains composed with
scipy's rotations, and hand-computed forces.
"""

import math

import numpy as np
import pytest
import trimesh
import warp as wp
from scipy.spatial.transform import Rotation

import ocean_warp as ow
from ocean_warp.eboat import EBoat, EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.eboat.offsets_hull import offsets_hull, parse_hull_offsets
from ocean_warp.eboat.parts import eboat_parts
from ocean_warp.eboat.urdf_links import urdf_links
from ocean_warp.frames import roll_pitch_yaw
from ocean_warp.kernels.appendage_buoyancy import appendage_buoyancy
from ocean_warp.kernels.spatial import vec6
from ocean_warp.stability import righting_arm_curve
from tests.waterlines import centre_of_volume_x, port_waterline, volume_by_waterlines, waterplane

SEA = 1025.0
BASE_Z = -0.094
"""Sheet, real geometry: at 158.4 kg in sea water the waterline is at base z +0.094; the body frame's origin
sits on it, so a point of the base frame lies 0.094 m lower in the body frame."""
CAD_TO_BASE_X, CAD_TO_BASE_Z = -1.24471, 0.40996
"""Sheet, real geometry: x_b = x - 1.24471, z_b = z + 0.40996 (the CAD hull frame to the base frame)."""
APPENDAGE_VOLUME = 0.0075356 + 0.0007586
"""Keel fin and bulb outside the hull (sheet: 7.5 L; vpp_inputs_real.json, measured V_keel_out) and the rudder
below it (V_rud_out) [m^3]: what the sheet's waterline counts besides the canoe body."""
SHEET_GZ = {10: 0.048, 20: 0.086, 30: 0.099, 40: 0.099, 50: 0.092, 60: 0.075}
"""Sheet, real geometry: GZ [m] of the real hull, keel and rudder with the URDF's centre of gravity."""


@pytest.fixture(scope="module")
def eboat():
    return EBoat()


def floating_level(triangles: np.ndarray, volume: float) -> float:
    """Height [m] of the plane below which the mesh holds ``volume`` [m^3], by Newton's method on the volume by
    waterlines, whose derivative is the waterplane area."""
    level = 0.0
    for _ in range(6):
        below, _ = volume_by_waterlines(triangles, level, slices=400)
        level -= (below - volume) / waterplane(triangles, level)[0]
    return level


def test_offsets_hull_is_closed_outward_and_where_the_cad_has_it(eboat):
    hull = eboat.hull
    mesh = hull.to_trimesh()
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0.0
    assert hull.triangle_count == 2024
    assert EBoat(EBoatConfig(hull_triangles=1000)).hull.triangle_count <= 1000
    assert EBoat(EBoatConfig(hull_triangles=512)).hull.triangle_count == 506
    low, high = hull.bounds
    # Sheet: 2.489 m long from the transom (CAD x = 0), 0.958 m beam at the sheer (CAD z = 0), the bottom 0.441 m
    # below the sheer at its deepest (the offsets table's deepest station).
    np.testing.assert_allclose([low[0], high[0]], [CAD_TO_BASE_X, 2.489 + CAD_TO_BASE_X], atol=1e-9)
    assert high[1] - low[1] == pytest.approx(0.958, abs=0.003)
    assert high[2] == pytest.approx(CAD_TO_BASE_Z + BASE_Z, abs=1e-9)
    assert high[2] - low[2] == pytest.approx(0.441, abs=0.001)
    # A plumb bow: the whole last station's face stands at the bow, its sheer about the sheet's 0.16 m wide.
    bow = hull.vertices[np.isclose(hull.vertices[:, 0], high[0])]
    assert np.ptp(bow[:, 2]) > 0.39
    assert np.ptp(bow[:, 1]) == pytest.approx(0.16, abs=0.03)


def section(triangles: np.ndarray, x: float) -> np.ndarray:
    """(S, 2, 2) segments (y, z) [m] where the mesh's triangles cross the plane at body ``x``."""
    side = triangles[:, :, 0] >= x
    cut = triangles[(side.sum(axis=1) == 1) | (side.sum(axis=1) == 2)]
    ends, crossings = [], []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        pa, pb = cut[:, a], cut[:, b]
        crosses = (pa[:, 0] >= x) != (pb[:, 0] >= x)
        t = (x - pa[:, 0]) / np.where(crosses, pb[:, 0] - pa[:, 0], 1.0)
        ends.append(pa[:, 1:] + t[:, None] * (pb[:, 1:] - pa[:, 1:]))
        crossings.append(crosses)
    return np.stack(ends, axis=1)[np.stack(crossings, axis=1)].reshape(-1, 2, 2)


def half_breadth(segments: np.ndarray, z: float) -> float:
    """Largest y [m] of the section ``segments`` at height ``z`` [m]."""
    spans = ((segments[:, 0, 1] - z) * (segments[:, 1, 1] - z) <= 0.0) & (np.ptp(segments[:, :, 1], axis=1) > 1e-12)
    seg = segments[spans]
    t = (z - seg[:, 0, 1]) / (seg[:, 1, 1] - seg[:, 0, 1])
    return float(np.max(seg[:, 0, 0] + t * (seg[:, 1, 0] - seg[:, 0, 0])))


@pytest.mark.parametrize("station, bottom, offsets", [
    (1.0, -0.4321, {-0.400: 0.4031, -0.300: 0.4210, -0.200: 0.4387, -0.100: 0.4563}),
    (2.0, -0.4247, {-0.400: 0.1828, -0.300: 0.2003, -0.200: 0.2177, -0.100: 0.2342}),
])
def test_loft_passes_through_the_offsets_table(eboat, station, bottom, offsets):
    """The default mesh cut at two of the table's stations (CAD x 1.0 and 2.0 m; rows typed from
    hull_offsets.csv): the bottom's height and the half-breadths at four waterlines, within 1.5 mm (the loft's
    stations fall between the table's: measured within 0.9 mm; the sides flare 3.6 mm per 20 mm waterline)."""
    triangles = eboat.hull.vertices[eboat.hull.triangles].astype(np.float64)
    cut = section(triangles, station + CAD_TO_BASE_X)
    assert cut[:, :, 1].min() - (CAD_TO_BASE_Z + BASE_Z) == pytest.approx(bottom, abs=0.0015)
    for z, expected in offsets.items():
        assert half_breadth(cut, z + CAD_TO_BASE_Z + BASE_Z) == pytest.approx(expected, abs=0.0015)


def test_floats_where_the_sheet_measured_it(eboat):
    """Sheet: at 158.4 kg in sea water the waterline lies at base z +0.094 (body z 0), canoe draft 0.125 m,
    L_wl 2.488 (the whole length), B_wl 0.847, waterplane 1.577 m^2, LCB 0.536 L_wl aft of the bow (the
    measurements beside it: 0.5325). The canoe body carries the weight less the appendages' displacement."""
    triangles = eboat.hull.vertices[eboat.hull.triangles].astype(np.float64)
    level = floating_level(triangles, 158.4 / SEA - APPENDAGE_VOLUME)
    assert level == pytest.approx(0.0, abs=0.002)
    assert level - triangles[:, :, 2].min() == pytest.approx(0.125, abs=0.002)
    segments = port_waterline(triangles, level)
    length = np.ptp(segments[:, :, 0])
    assert length == pytest.approx(2.488, abs=0.01)
    assert 2.0 * segments[:, :, 1].max() == pytest.approx(0.847, abs=0.005)
    assert waterplane(triangles, level)[0] == pytest.approx(1.577, rel=0.01)
    lcb = (segments[:, :, 0].max() - centre_of_volume_x(triangles, level, slices=400)) / length
    assert lcb == pytest.approx(0.536, abs=0.006)
    # The simulator's own rest height (its hull pass, with the appendages' buoyancy) and the hull form the
    # resistance reads agree, for the boat as composed (158.45 kg).
    rest = floating_level(triangles, eboat.mass_properties.mass / SEA - APPENDAGE_VOLUME)
    assert eboat.rest_height() == pytest.approx(-rest, abs=3e-4)
    form = eboat.hull_form
    assert form.canoe_draft == pytest.approx(0.125, abs=0.002)
    assert form.waterline_length == pytest.approx(2.488, abs=0.01)
    assert form.waterline_beam == pytest.approx(0.847, abs=0.005)
    assert form.waterplane_area == pytest.approx(1.577, rel=0.01)
    assert form.lcb_fraction == pytest.approx(0.536, abs=0.006)


def test_links_compose_to_the_sheets_mass_and_centre_of_gravity(eboat):
    """Sheet: every link through the URDF's joint chain, 158.45 kg with its centre of gravity at (-0.132, 0,
    +0.190) in the base frame. Two chains that turn (the sail hung from the boom through a rope link rolled 90
    deg; the port rack yawed and rolled on its support) composed here with scipy (URDF rpy: extrinsic x-y-z)."""
    mp = eboat.mass_properties
    assert mp.mass == pytest.approx(158.45, abs=0.005)
    np.testing.assert_allclose(mp.center_of_mass - [0.0, 0.0, BASE_Z], [-0.132, 0.0, 0.190], atol=0.0012)
    links = {link.name: link for link in urdf_links()}
    hull_joint = np.array([0.0, 0.0, 0.210586])
    # Sail: base <- hull <- mast (0.59529, 0, -0.153011) <- boom (-0.049, 0, 0.933) <- rope_c (-1.7978, 0, 0.0223;
    # roll 1.5708) <- sail (0.0140742, 0.0441151, 0); its CoM (1.10322, 1.09346, 0) in the sail's frame.
    roll = Rotation.from_euler("xyz", [1.5708, 0.0, 0.0])
    boom = hull_joint + [0.59529, 0.0, -0.153011] + [-0.049, 0.0, 0.933]
    sail = boom + [-1.7978, 0.0, 0.0223] + roll.apply(np.array([0.0140742, 0.0441151, 0.0]) + [1.10322, 1.09346, 0.0])
    np.testing.assert_allclose(links["sail"].center_of_mass, sail, atol=1e-9)
    assert sail[2] == pytest.approx(2.15, abs=0.005), "the sheet's sail centroid, z_b 2.15 m"
    # Port rack: hull <- deck (-1.24471, 0, 0.199376) <- support (2.44761, 0.0712925, 0.05) <- rack (0.0126828,
    # 0.0159808, 0.0899999; rpy -1.5708, 0, -0.372391); CoM (-1.21877, -0.00999996, -0.172045).
    turn = Rotation.from_euler("xyz", [-1.5708, -1.50078e-14, -0.372391])
    rack = (hull_joint + [-1.24471, 0.0, 0.199376] + [2.44761, 0.0712925, 0.05] + [0.0126828, 0.0159808, 0.0899999]
            + turn.apply([-1.21877, -0.00999996, -0.172045]))
    np.testing.assert_allclose(links["rack port"].center_of_mass, rack, atol=1e-9)
    urdf = np.array([[0.145894, 0.307705, -0.11957], [0.307705, 0.813431, 0.0467072], [-0.11957, 0.0467072, 0.908646]])
    np.testing.assert_allclose(links["rack port"].inertia, turn.as_matrix() @ urdf @ turn.as_matrix().T, atol=1e-12)
    # V-A keeps its 4.2 kg lighter hull (sheet: 154.2 against 158.4 kg); V-B is eboat4, as V-C.
    assert EBoat(EBoatConfig(version="V-A")).mass_properties.mass == pytest.approx(mp.mass - 4.2, abs=1e-9)
    assert EBoat(EBoatConfig(version="V-B")).mass_properties.mass == pytest.approx(mp.mass, abs=1e-12)


def test_righting_arm_is_the_sheets(eboat):
    """Sheet: GM 0.277 m; GZ 0.048 / 0.086 / 0.099 / 0.099 / 0.092 / 0.075 m at 10 ... 60 deg; the largest
    0.100 m at 35 deg (155 N m). The curve: ``ocean_warp.stability`` on the mesh, free in heave and trim, the
    keel, bulb and rudder floating with it (as the simulator's appendage buoyancy). GM: the slope at 1 deg
    without the list arm GZ(0) of the URDF's centre of gravity, 0.17 mm to port."""
    mp = eboat.mass_properties
    curve = righting_arm_curve(eboat.hull, mp.mass, mp.center_of_mass, np.radians([0.0, 1.0, *SHEET_GZ]),
                               appendages=eboat.appendages)
    upright, small, *rest = curve.righting_arm
    gm = (small - upright * math.cos(math.radians(1.0))) / math.sin(math.radians(1.0))
    assert gm == pytest.approx(0.277, rel=0.02)
    np.testing.assert_allclose(rest, list(SHEET_GZ.values()), atol=0.004)
    peak = righting_arm_curve(eboat.hull, mp.mass, mp.center_of_mass, np.radians(np.arange(28.0, 43.0, 1.0)),
                              appendages=eboat.appendages)
    top = int(np.argmax(peak.righting_arm))
    assert peak.righting_arm[top] == pytest.approx(0.100, abs=0.002)
    assert math.degrees(peak.heel[top]) == pytest.approx(35.0, abs=4.0)
    assert peak.righting_moment()[top] == pytest.approx(155.0, rel=0.02)


def test_foils_act_at_their_quarter_chords_on_their_real_planforms(eboat):
    """Sheet, real geometry: keel fin 0.235 m chord, t/c 0.106, 0.74 m span outside the hull, its quarter chord
    at x_b -0.081; rudder 0.0991 m^2 on a 0.617 m span, chord 0.170 to 0.145 m, its stock at x_b -1.086 near
    mid-chord, centroid z_b -0.237; sail centroid z_b 2.15 m. The keel's root: the offsets table's bottom under
    the fin (CAD x 1.164: between -0.4360 at 1.1 and -0.4389 at 1.2)."""
    keel, rudder = eboat.keel, eboat.rudder
    assert (keel.span, keel.root_chord, keel.tip_chord, keel.thickness_ratio) == (0.74, 0.235, 0.235, 0.106)
    assert rudder.span == 0.617 and rudder.area == pytest.approx(0.0991, rel=1e-9)
    assert rudder.tip_chord / rudder.root_chord == pytest.approx(0.145 / 0.170, rel=1e-9)
    rig = eboat.rig_parameters(SEA)
    keel_root = np.interp(1.24471 - 0.081, [1.1, 1.2], [-0.4360, -0.4389]) + CAD_TO_BASE_Z + BASE_Z
    np.testing.assert_allclose(np.array(rig.keel_center), [-0.081, 0.0, keel_root - 0.74 / 2.0], atol=0.008)
    assert rig.keel_area == pytest.approx(0.235 * 0.74, rel=1e-6)
    x, y, z = np.array(rig.rudder_center)
    assert -1.086 + 0.145 / 4.0 <= x <= -1.086 + 0.175 / 4.0 and y == 0.0
    assert z == pytest.approx(-0.237 + BASE_Z, abs=1e-6)
    assert rig.rudder_area == pytest.approx(0.0991, rel=1e-6)
    assert rig.sail_height == pytest.approx(2.15 + BASE_Z, abs=1e-6)
    # The seed profile keeps the sheet's centres of effort in the base frame, and its four buoyancy points.
    seed = EBoat(EBoatConfig(profile="seed"))
    seed_rig = seed.rig_parameters(997.0)
    np.testing.assert_allclose(np.array(seed_rig.keel_center), [-0.135, 0.0, -0.40 + BASE_Z], atol=1e-6)
    assert seed_rig.sail_height == pytest.approx(1.5 + BASE_Z, abs=1e-6)
    points = seed.point_buoyancy("cpu", ow.WaterConfig(density=997.0)).points.numpy()
    np.testing.assert_allclose(points, [[0.6, 0.45, BASE_Z], [-0.6, 0.45, BASE_Z], [0.6, -0.45, BASE_Z],
                                        [-0.6, -0.45, BASE_Z]], atol=1e-7)


def test_parts_draw_the_real_boat():
    """The drawn sail's centroid at the sheet's z_b 2.15 m (area about its 3.188 m^2); the keel fin's leading
    edge at x_b -0.022, the bulb's bottom 0.061 m below its centre at z_b -0.825; the boom's and the rudder's
    pivots at the URDF's boom and rudder joints."""
    parts = eboat_parts(hull_detail=1)
    sail = trimesh.Trimesh(parts.sail.points, parts.sail.triangles(), process=False)
    assert sail.area == pytest.approx(3.188, rel=0.01)
    centroid = (sail.triangles_center * sail.area_faces[:, None]).sum(axis=0) / sail.area
    assert centroid[2] + parts.boom_pivot[2] - BASE_Z == pytest.approx(2.15, abs=0.005)
    fin = parts.keel.points[parts.keel.points[:, 2] > -0.825 + 0.061 + BASE_Z + 1e-6]  # above the bulb
    assert fin[:, 0].max() == pytest.approx(-0.022, abs=1e-6)
    assert parts.keel.points[:, 2].min() == pytest.approx(-0.825 - 0.061 + BASE_Z, abs=1e-6)
    np.testing.assert_allclose(parts.boom_pivot, [0.59529 - 0.049, 0.0, 0.210586 - 0.153011 + 0.933 + BASE_Z])
    np.testing.assert_allclose(parts.rudder_pivot, [-1.08641, 0.0, 0.210586 + 0.0764342 + BASE_Z])
    # The blade hangs from the hull's bottom near the transom (the sheet's 0.617 m span below its root).
    blade_depth = -parts.blade.points[:, 2].min() - (parts.rudder_pivot[2] - (-0.237 + BASE_Z))
    assert blade_depth == pytest.approx(0.617 - 0.617 / 3.0 * (0.170 + 2 * 0.145) / (0.170 + 0.145), abs=1e-6)


def test_lead_bulb_puts_the_centre_of_gravity_below_the_waterline():
    """Sheet: a 44 kg lead bulb on a GRP fin would put the centre of gravity 0.03-0.05 m below the waterline (an
    assumption). Here: the URDF's 40.04 kg keel replaced by the 44 kg bulb and a fin of 3.63 L of solid GRP at
    1900 kg/m^3 (assumed); the waterline found by waterlines for the heavier boat."""
    eboat = EBoat(EBoatConfig(ballast="lead_bulb"))
    mp = eboat.mass_properties
    assert mp.mass == pytest.approx(158.4451 - 40.0429 + 44.0 + 0.0036277 * 1900.0, abs=1e-3)
    triangles = eboat.hull.vertices[eboat.hull.triangles].astype(np.float64)
    level = floating_level(triangles, mp.mass / SEA - APPENDAGE_VOLUME)
    assert -0.05 <= mp.center_of_mass[2] - level <= -0.03
    with pytest.raises(ValueError, match="EBoatConfig.ballast 'lead_bulb' changes the real boat's keel"):
        EBoatConfig(hull="procedural", ballast="lead_bulb")
    with pytest.raises(ValueError, match="EBoatConfig.ballast must be one of 'cad', 'lead_bulb'"):
        EBoatConfig(ballast="iron")
    with pytest.raises(ValueError, match="EBoatConfig.hull must be one of 'real', 'procedural'"):
        EBoatConfig(hull="canoe")


def test_appendage_buoyancy_pushes_up_at_the_centroid_and_fades_at_the_surface(device, rng):
    """Four boats in still water at random attitudes (up to 30 deg), their appendages' centroid deep, 0.1 m
    below the surface, at it and 0.3 m above: rho g V (1, 1/2 + 0.1 / 0.5, 1/2, 0) straight up at the centroid,
    in the body frame, as a wrench about the origin (the band 0.5 m)."""
    eboat = EBoat()
    water = ow.WaterConfig()
    model = eboat.appendage_buoyancy(water)
    ocean = ow.Ocean(ow.OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.0), device=device)
    ocean.update(0.0)
    turns = Rotation.from_rotvec(rng.normal(size=(4, 3)) * np.radians(30.0) / math.sqrt(3.0))
    center = np.array(eboat.geometry.appendage_center)
    depths = np.array([2.0, 0.1, 0.0, -0.3])
    positions = np.column_stack([np.zeros((4, 2)), -depths - turns.apply(center)[:, 2]])
    wrench = wp.zeros(4, dtype=vec6, device=device)
    wp.launch(appendage_buoyancy, dim=4, device=device,
              inputs=[model, ocean.surface, wp.array(positions, dtype=wp.vec3, device=device),
                      wp.array(turns.as_quat(), dtype=wp.quat, device=device)], outputs=[wrench])
    lift = water.density * water.gravity * APPENDAGE_VOLUME * np.array([1.0, 0.7, 0.5, 0.0])
    force = turns.inv().apply(np.column_stack([np.zeros((4, 2)), lift]))
    expected = np.column_stack([force, np.cross(center, force)])
    np.testing.assert_allclose(wrench.numpy(), expected, atol=2e-3 * lift[0])


def test_real_boat_rests_upright_near_its_origin_in_the_simulator(device):
    """The mesh boat with its appendages' buoyancy, let go 5 cm high and 5 cm deep, settles upright (trimmed
    by the stern: the URDF's centre of gravity lies 4 cm aft of the centre of buoyancy) with its origin within
    5 mm of the still water, where the sheet's waterline puts it."""
    config = EBoatSimulatorConfig(wind=ow.WindConfig(speed=0.0))
    sim = EBoatSimulator(config, 2, device=device)
    sim.reset(position=[[0.0, 0.0, 0.05], [10.0, 0.0, -0.05]])
    for _ in range(400):
        sim.step()
    state = sim.fleet.numpy()
    assert np.all(np.abs(state["position"][:, 2]) < 0.005)
    roll, pitch, _ = roll_pitch_yaw(state["orientation"]).T
    assert np.all(np.abs(np.degrees(roll)) < 0.5) and np.all(np.degrees(pitch) < 0.0)
    assert np.all(np.degrees(pitch) > -2.0)


def test_bad_offsets_tables_are_refused():
    good = ("x_m,bottom_z_m,y_at_bottom_plus_3mm,y_at_z-0.200,y_at_z-0.100\n"
            "0.0,-0.3,0.30,0.32,0.34\n1.0,-0.3,0.30,0.32,0.34\n")
    offsets = parse_hull_offsets(good)
    assert len(offsets.stations) == 2 and offsets.length == 1.0
    # A table's own hull: 1 m from the transom, its sides flaring 0.02 m per 0.1 m up to 0.36 m at the sheer.
    box = offsets_hull(4, 3, offsets=offsets)
    assert np.ptp(box.vertices[:, 0]) == pytest.approx(1.0) and np.ptp(box.vertices[:, 1]) == pytest.approx(0.72)
    with pytest.raises(ValueError, match="the stations must lie in \\[0, length\\]"):
        parse_hull_offsets(good, length=0.5)
    with pytest.raises(ValueError, match="header must start x_m, bottom_z_m, y_at_bottom_plus_3mm"):
        parse_hull_offsets(good.replace("x_m", "station"))
    with pytest.raises(ValueError, match="waterline columns must be named y_at_z<height>"):
        parse_hull_offsets(good.replace("y_at_z-0.100", "y_at_sheer"))
    with pytest.raises(ValueError, match="HullOffsets.stations must be finite and strictly increasing"):
        parse_hull_offsets(good.replace("1.0,-0.3", "0.0,-0.3"))
    with pytest.raises(ValueError, match="the section at x = 1.0 m must have increasing heights"):
        parse_hull_offsets(good.replace("1.0,-0.3,", "1.0,-0.15,"))
