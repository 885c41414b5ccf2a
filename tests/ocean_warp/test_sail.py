"""The physics profile's main and windage: the ORC's published main coefficients, the lifting line's induced
drag, a stalled sail's normal force, depowering by easing, the loss of drive with heel and the windage's
blend, each against numbers worked by hand here."""

import math

import numpy as np
import pytest
import warp as wp

from ocean_warp.eboat import EBoat, EBoatConfig
from ocean_warp.kernels.foils import foil_force
from ocean_warp.sail import Mainsail

# The ORC main ("high"), C_L and C_Dp at apparent wind angles 0, 7, 9, 12, 28 deg (ORC VPP documentation;
# python-vpp 1.0.0 dat/main.dat), and its quadratic viscous drag k_p.
ORC_SHEETED_IN = {0: (0.0, 0.03448), 7: (0.94828, 0.01724), 9: (1.13793, 0.01466), 12: (1.25, 0.01466),
                  28: (1.42681, 0.02586)}
ORC_KP = 0.01379


@pytest.mark.parametrize("flogs_below", [0.0, None])
def test_sheeted_in_points_and_induced_drag(rng, flogs_below):
    """The ORC's points (luff_deg 0), or for a main alone the same points spread from [0, 28] over [luff_deg, 28]
    deg, with C_D = C_Dp + (k_p + 1 / (pi AR_e)) C_L^2, AR_e = (1.1 (P + BAD))^2 / A; flogging below luff_deg."""
    area, luff, bad = rng.uniform(2.0, 6.0), rng.uniform(2.5, 5.0), rng.uniform(0.0, 0.3)
    luff_deg = rng.uniform(2.0, 15.0) if flogs_below is None else flogs_below
    sail = Mainsail(area=area, luff=luff, boom_above_deck=bad, luff_deg=luff_deg)
    induced = 1.0 / (math.pi * (1.1 * (luff + bad)) ** 2 / area)
    for degrees, (lift, parasitic) in ORC_SHEETED_IN.items():
        cl, cd = sail.coefficients(math.radians(luff_deg + degrees * (28.0 - luff_deg) / 28.0))
        assert cl == pytest.approx(lift, abs=1e-9)
        assert cd == pytest.approx(parasitic + (ORC_KP + induced) * lift**2, abs=1e-9)
    flogging = np.radians(rng.uniform(0.0, luff_deg, size=4))
    cl, cd = sail.coefficients(flogging)
    np.testing.assert_allclose(cl, 0.0, atol=1e-12)
    np.testing.assert_allclose(cd, 0.03448, atol=1e-12)


def test_lift_rises_monotonically_while_sheeted_in():
    cl, _ = Mainsail(area=3.0, luff=3.2, boom_above_deck=0.1).coefficients(np.radians(np.linspace(0.0, 28.0, 281)))
    assert np.all(np.diff(cl) >= -1e-12)


def test_separated_sail_pushes_normal_to_its_chord(rng):
    """Past 45 deg the force is C_N = 1.34 normal to the chord: C_D / C_L = tan(alpha) and C_L^2 + C_D^2 = C_N^2
    (up to 135 deg); the ORC's points at 120 and 150 deg apparent, read as such a sail, give C_N 1.34-1.37."""
    sail = Mainsail(area=3.0, luff=3.2, boom_above_deck=0.1)
    alpha = np.radians(rng.uniform(46.0, 134.0, size=8))
    cl, cd = sail.coefficients(alpha)
    np.testing.assert_allclose(np.hypot(cl, cd), 1.34, rtol=1e-9)
    np.testing.assert_allclose(cd * np.cos(alpha), cl * np.sin(alpha), atol=1e-9)
    for lift, drag in ((0.93103, 0.96888), (0.38793, 1.31578)):
        assert math.hypot(lift, drag) == pytest.approx(1.34, rel=0.03)


def test_coefficients_odd_and_even_and_bad_input():
    sail = Mainsail(area=3.0, luff=3.2, boom_above_deck=0.1)
    alpha = np.radians([3.0, 17.0, 60.0, 150.0])
    cl, cd = sail.coefficients(alpha)
    minus_cl, minus_cd = sail.coefficients(-alpha)
    np.testing.assert_allclose(minus_cl, -cl)
    np.testing.assert_allclose(minus_cd, cd)
    for field, value in (("area", -1.0), ("luff", float("nan")), ("boom_above_deck", -0.1), ("normal_force", 3.0)):
        kwargs = dict(area=3.0, luff=3.2, boom_above_deck=0.1) | {field: value}
        with pytest.raises(ValueError, match=field):
            Mainsail(**kwargs)
    with pytest.raises(ValueError, match="alpha"):
        sail.coefficients(float("nan"))


@wp.kernel
def _sail_forces(flows: wp.array(dtype=wp.vec3), chords: wp.array(dtype=wp.vec3), spans: wp.array(dtype=wp.vec3),
                 area: float, lift: wp.array(dtype=float), drag: wp.array(dtype=float), out: wp.array(dtype=wp.vec4)):
    i = wp.tid()
    out[i] = foil_force(flows[i], chords[i], spans[i], area, 1.2, lift, drag, 3.14159265)


def _kernel_forces(device, flows, chords, spans, area, tables):
    arrays = [wp.array(np.asarray(v, np.float32), dtype=wp.vec3, device=device) for v in (flows, chords, spans)]
    lift, drag = (wp.array(t.astype(np.float32), dtype=float, device=device) for t in tables)
    out = wp.zeros(len(flows), dtype=wp.vec4, device=device)
    wp.launch(_sail_forces, dim=len(flows), inputs=[*arrays, area, lift, drag, out], device=device)
    return out.numpy()


def _from_tables(tables, alpha: float) -> tuple[float, float]:
    """C_L, C_D read from 1-degree tables as the kernel reads them (linear), at ``alpha`` [rad]."""
    degrees = math.degrees(alpha)
    grid = np.arange(181.0)
    return np.sign(degrees) * np.interp(abs(degrees), grid, tables[0]), np.interp(abs(degrees), grid, tables[1])


def test_easing_the_sheet_depowers(device):
    """Close-hauled (apparent wind 25 deg off the bow), the heeling force falls as the boom is eased from 5 to 17 deg:
    the angle of attack drops from 20 to 8 deg, where the main alone luffs."""
    sail = Mainsail(area=3.188, luff=3.16, boom_above_deck=0.07)
    booms = np.radians(np.arange(5.0, 18.0, 3.0))
    awa = math.radians(25.0)
    flow = 6.0 * np.array([-math.cos(awa), math.sin(awa), 0.0])  # from the starboard bow; the boom to port
    chords = np.column_stack([-np.cos(booms), np.sin(booms), np.zeros_like(booms)])
    forces = _kernel_forces(device, np.tile(flow, (len(booms), 1)), chords, np.tile([0, 0, 1.0], (len(booms), 1)),
                            3.188, sail.tables())
    heeling = forces[:, 1]
    assert np.all(heeling > 0.0) and np.all(np.diff(heeling) < 0.0)
    for k, boom in enumerate(booms):  # by hand: 1/2 rho A V^2 (C_L z x d + C_D d), alpha from the chord to d about z
        cl, cd = _from_tables(sail.tables(), boom - awa)
        d = flow / 6.0
        across = np.array([-d[1], d[0], 0.0])  # z x d
        expected = 0.5 * 1.2 * 3.188 * 36.0 * (cl * across + cd * d)
        np.testing.assert_allclose(forces[k, :3], expected, rtol=2e-3, atol=2e-3)


def test_heel_reduces_the_force_as_cos_squared(device, rng):
    """A horizontal beam wind on a mast heeled by phi: only the flow normal to the mast counts, so the force is
    cos^2(phi) of the upright one at the same angle of attack."""
    sail = Mainsail(area=3.188, luff=3.16, boom_above_deck=0.07)
    heel = np.radians(rng.uniform(5.0, 40.0, size=4))
    boom = math.radians(60.0)
    chord = np.array([-math.cos(boom), math.sin(boom), 0.0])
    spans = np.column_stack([np.zeros_like(heel), -np.sin(heel), np.cos(heel)])  # rolled about x with the boom
    chords = np.column_stack([np.full_like(heel, chord[0]), chord[1] * np.cos(heel), chord[1] * np.sin(heel)])
    flow = np.array([0.0, -7.0, 0.0])
    heeled = _kernel_forces(device, np.tile(flow, (len(heel), 1)), chords, spans, 3.188, sail.tables())
    upright = _kernel_forces(device, flow[None, :], chord[None, :], np.array([[0, 0, 1.0]]), 3.188, sail.tables())
    np.testing.assert_allclose(heeled[:, 3], upright[0, 3], atol=2e-5)  # same angle of attack
    np.testing.assert_allclose(np.linalg.norm(heeled[:, :3], axis=1),
                               np.cos(heel) ** 2 * np.linalg.norm(upright[0, :3]), rtol=2e-3)


def test_physics_windage_blends_ahead_and_abeam(device, rng):
    """A boat at rest in still water, sheeted in, in a uniform wind from a random angle off the bow: the rig's force
    is the sail's (its table, by hand) plus the windage 1/2 rho A(theta) |w| w with the ORC's blend A = A_ahead
    cos^2 + A_abeam sin^2 of the wind's angle off the bow, A = 0.816 x the mesh's projected topsides."""
    from ocean_warp.eboat import EBoatSimulator, EBoatSimulatorConfig
    from ocean_warp.wind import WindConfig

    boat = EBoat(EBoatConfig())
    ahead, abeam = 0.816 * boat.topsides.area_ahead, 0.816 * boat.topsides.area_abeam
    rho = float(boat.rig_parameters(1025.0).air_density)
    lift_table, drag_table = boat.mainsail.tables()
    speed, towards = rng.uniform(3.0, 9.0), rng.uniform(-math.pi, math.pi)
    sim = EBoatSimulator(EBoatSimulatorConfig(boat=EBoatConfig(), wind=WindConfig(speed=speed, direction=towards)), 1,
                         device=device)
    sim.reset(position=[0.0, 0.0, 0.0], heading=0.0, velocity=[0, 0, 0, 0, 0, 0], wind_speed=speed,
              wind_direction=towards, sheet=0.0)
    sim.fleet.forces.model_wrench.zero_()
    sim.rig.substep(sim.simulator)
    force = sim.fleet.forces.model_wrench.numpy()[0, :2]
    wind = speed * np.array([math.cos(towards), math.sin(towards)])
    d = wind / speed
    cl, cd = _from_tables((lift_table, drag_table), math.atan2(-d[1], -d[0]))  # from the boom (aft) to the flow
    sail = 0.5 * rho * boat.mainsail.area * speed**2 * (cl * np.array([-d[1], d[0]]) + cd * d)
    windage = 0.5 * rho * (ahead * d[0] ** 2 + abeam * d[1] ** 2) * speed * wind
    np.testing.assert_allclose(force, sail + windage, rtol=2e-3, atol=2e-3)
