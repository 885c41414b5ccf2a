"""The database's added mass and radiation drive in the heading frame (``kernels.seakeeping_frame``), against
the water's impulse differentiated in numpy, analytic cases of a heeled hull, and the unchanged path of hulls
without a database."""

import math

import numpy as np
import pytest
import warp as wp

import ocean_warp as ow
from ocean_warp.frames import quaternion_from_roll_pitch_yaw
from ocean_warp.kernels.radiation import advance_radiation_terms
from ocean_warp.kernels.rigid_body import added_mass_coriolis
from ocean_warp.kernels.seakeeping_frame import heading_frame_added_mass, heading_tilt
from ocean_warp.kernels.spatial import vec6
from ocean_warp.radiation import zero_order_hold
from ocean_warp.seakeeping.eboat_database import eboat_hydro_database
from tests.hull_setups import calm_ocean
from tests.ocean_warp.test_radiation import heave_database

mat66 = wp.types.matrix(shape=(6, 6), dtype=wp.float32)


@wp.kernel
def _heading_terms(orientation: wp.array(dtype=wp.quat), nu_r: wp.array(dtype=vec6), added: wp.array(dtype=mat66),
                   mass: wp.array(dtype=mat66), terms: wp.array(dtype=vec6), jacobian: wp.array(dtype=mat66),
                   body_fixed: wp.array(dtype=vec6)):
    i = wp.tid()
    out = heading_frame_added_mass(heading_tilt(orientation[i]), nu_r[i], added[0])
    mass[i] = out.mass
    terms[i] = out.terms
    jacobian[i] = out.jacobian
    body_fixed[i] = added_mass_coriolis(nu_r[i], added[0])


def heading_terms(device, quaternions, velocities, added):
    """(mass (N, 6, 6), terms (N, 6), jacobian (N, 6, 6), Kirchhoff's body-fixed terms (N, 6)) from the kernel."""
    n = len(quaternions)
    arrays = [wp.zeros(n, dtype=t, device=device) for t in (mat66, vec6, mat66, vec6)]
    wp.launch(_heading_terms, dim=n, device=device,
              inputs=[wp.array(np.asarray(quaternions, np.float32), dtype=wp.quat, device=device),
                      wp.array(np.asarray(velocities, np.float32), dtype=vec6, device=device),
                      wp.array(np.asarray(added, np.float32)[None], dtype=mat66, device=device)],
              outputs=arrays)
    return tuple(a.numpy().astype(np.float64) for a in arrays)


def euler_matrix(roll, pitch, yaw):
    """Z-Y-X body -> world rotation."""
    cr, sr, cp, sp, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return rz @ ry @ rx, rz


def random_added_mass(rng):
    """A symmetric positive definite 6x6 with a heave term far above the sway term, as a planing hull's."""
    root = rng.normal(size=(6, 6)) * np.array([2.0, 3.0, 4.0, 1.0, 2.0, 1.0])
    return root @ root.T + np.diag([4.0, 20.0, 400.0, 8.0, 120.0, 6.0])


def test_added_mass_load_is_minus_the_rate_of_the_waters_impulse_in_the_heading_frame(device, rng):
    """Along a prescribed heeling, trimming, turning and drifting motion the kernel's load -(M_A dnu/dt + c_A)
    equals -(dP/dt, dL/dt + v x P) of the water's impulse (P, L) = R_z(psi) A nu_h, differentiated numerically
    in the world frame (Lamb's impulse theorem about the moving origin), for a random added-mass matrix."""
    added = random_added_mass(rng)
    a = rng.uniform(0.2, 0.8, size=(3, 3))  # amplitudes of roll, pitch, yaw [rad], and of the three speeds
    f = rng.uniform(0.5, 2.0, size=(2, 3))  # their angular frequencies [rad/s]
    speed = rng.uniform(-1.5, 1.5, size=3)

    def angles(t):
        return np.array([a[0, 0] * np.sin(f[0, 0] * t) + 0.6, a[0, 1] * 0.4 * np.sin(f[0, 1] * t), a[0, 2] * t])

    def linear_body(t):
        return speed + a[1] * np.sin(f[1] * t)

    def state(t):
        """(R, R_z, nu_b) at t: the body angular velocity from R^T dR/dt (central differences of R)."""
        rotation, turn = euler_matrix(*angles(t))
        h = 1e-6
        rate = rotation.T @ (euler_matrix(*angles(t + h))[0] - euler_matrix(*angles(t - h))[0]) / (2 * h)
        omega = np.array([rate[2, 1], rate[0, 2], rate[1, 0]])
        return rotation, turn, np.concatenate([linear_body(t), omega])

    def impulse(t):
        rotation, turn, nu = state(t)
        tilt = turn.T @ rotation
        p = added @ np.concatenate([tilt @ nu[:3], tilt @ nu[3:]])
        return turn @ p[:3], turn @ p[3:]

    times = rng.uniform(0.0, 3.0, size=6)
    h = 1e-4
    expected, quats, nus, accelerations = [], [], [], []
    for t in times:
        rotation, _, nu = state(t)
        (p_plus, l_plus), (p_minus, l_minus) = impulse(t + h), impulse(t - h)
        force = -(p_plus - p_minus) / (2 * h)
        moment = -((l_plus - l_minus) / (2 * h) + np.cross(rotation @ nu[:3], impulse(t)[0]))
        expected.append(np.concatenate([rotation.T @ force, rotation.T @ moment]))
        quats.append(quaternion_from_roll_pitch_yaw(angles(t))[0])
        nus.append(nu)
        accelerations.append((state(t + h)[2] - state(t - h)[2]) / (2 * h))
    mass, terms, _, _ = heading_terms(device, quats, nus, added)
    load = -(np.einsum("nij,nj->ni", mass, np.array(accelerations)) + terms)
    scale = np.abs(np.array(expected)).max()
    np.testing.assert_allclose(load, np.array(expected), atol=2e-4 * scale)


def test_jacobian_is_the_derivative_of_the_velocity_terms(device, rng):
    """The analytic d c_A / d nu against central differences of the kernel's c_A (float64 steps of 1e-2 on a
    quadratic form: exact but for float32 rounding)."""
    added = random_added_mass(rng)
    quat = quaternion_from_roll_pitch_yaw([[0.7, -0.25, 1.1]])[0]
    nu = rng.normal(size=6)
    step = 1e-2
    rows = [nu] + [nu + s * step * np.eye(6)[k] for k in range(6) for s in (1.0, -1.0)]
    _, terms, jacobian, _ = heading_terms(device, [quat] * len(rows), rows, added)
    numeric = np.column_stack([(terms[1 + 2 * k] - terms[2 + 2 * k]) / (2 * step) for k in range(6)])
    np.testing.assert_allclose(jacobian[0], numeric, atol=2e-3 * np.abs(numeric).max())


def test_hull_heeled_90_deg_drifting_sideways_meets_the_upright_sway_added_mass(device):
    """The E-Boat's A_inf: heeled 90 deg, an acceleration across the world (along the body z axis) meets A22
    (22.7 kg), not the heave term A33 (432 kg) that body-fixed added mass would put there; upright, the body-frame
    added mass is A_inf itself."""
    added = np.asarray(eboat_hydro_database().added_mass_infinite, dtype=np.float64)
    heeled = quaternion_from_roll_pitch_yaw([[math.pi / 2, 0.0, 0.4]])[0]
    upright = quaternion_from_roll_pitch_yaw([[0.0, 0.0, 0.4]])[0]
    mass, _, _, _ = heading_terms(device, [heeled, upright], [np.zeros(6)] * 2, added)
    rotation, _ = euler_matrix(math.pi / 2, 0.0, 0.4)
    across = rotation.T @ np.array([-math.sin(0.4), math.cos(0.4), 0.0])  # the world's horizontal, abeam
    acceleration = np.concatenate([across, np.zeros(3)])
    force_world = rotation @ (mass[0] @ acceleration)[:3]
    assert abs(force_world @ rotation @ across - added[1, 1]) < 1e-3 * added[1, 1]
    assert abs(across[2]) > 0.999  # abeam is the body z axis: a body-fixed A_inf would give A33 here
    np.testing.assert_allclose(mass[1], added, atol=1e-3 * np.abs(added).max())


@pytest.mark.parametrize("heel_deg", [0.0, 30.0, 60.0])
def test_heeled_hull_sailing_with_leeway_feels_the_upright_munk_moment(device, rng, heel_deg):
    """Sailing at u with a horizontal leeway v, heeled or not, a diagonal A_inf gives the water's yaw moment about
    the vertical of the upright Munk moment, -(A22 - A11) u v (Fossen 2011, eq. 6.55, the yaw term of
    C_A nu): the heave added mass does not see the leeway. Body-fixed A_inf gives a world-yaw moment that grows
    with the heel (the knockdown's broach)."""
    added = np.diag([3.8, 22.7, 432.0, 7.9, 125.9, 6.5])
    u, v = rng.uniform(0.8, 2.0), rng.uniform(0.1, 0.4)
    heel, yaw = math.radians(heel_deg), rng.uniform(-math.pi, math.pi)
    rotation, turn = euler_matrix(heel, 0.0, yaw)
    velocity_world = turn @ np.array([u, v, 0.0])
    nu = np.concatenate([rotation.T @ velocity_world, np.zeros(3)])
    quat = quaternion_from_roll_pitch_yaw([[heel, 0.0, yaw]])[0]
    _, terms, _, body_fixed = heading_terms(device, [quat], [nu], added)
    world_yaw = -(rotation @ terms[0, 3:])[2]
    expected = -(added[1, 1] - added[0, 0]) * u * v
    assert abs(world_yaw - expected) < 1e-4 * abs(expected) + 1e-4
    body_fixed_yaw = -(rotation @ body_fixed[0, 3:])[2]
    if heel_deg == 0.0:
        assert abs(body_fixed_yaw - expected) < 1e-4 * abs(expected) + 1e-4
    else:  # (A11 - A33) u w_b, w_b = -v sin(heel), turned into the vertical by sin(heel)
        assert abs(body_fixed_yaw - expected) > 5.0 * abs(expected) * math.sin(heel) ** 2


def test_radiation_memory_is_driven_by_the_heading_frames_velocity(device, rng):
    """A box with a heave-only radiation kernel, heeled 90 deg: a drift across the world (along its body z axis)
    drives nothing; a vertical motion (along its body y axis) drives the heave kernel by C Gamma w, the numpy
    zero-order hold of the term."""
    database = heave_database(rng)
    boat = ow.BoatType(hull=ow.Hull.box(2.0, 1.0, 0.6), mass=400.0, seakeeping=database)
    fleet = ow.Fleet([boat], count=2, device=device)
    heel = quaternion_from_roll_pitch_yaw([[math.pi / 2, 0.0, 0.3]])
    rotation, turn = euler_matrix(math.pi / 2, 0.0, 0.3)
    rise = rng.uniform(0.1, 0.5)
    across = rotation.T @ turn @ np.array([0.0, 0.4, 0.0])
    upward = rotation.T @ np.array([0.0, 0.0, rise])
    fleet.reset(position=[[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]], orientation=np.repeat(heel, 2, axis=0),
                velocity=[np.concatenate([across, np.zeros(3)]), np.concatenate([upward, np.zeros(3)])])
    substep = 0.01
    simulator = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(dt=substep, substeps=1))
    wp.launch(advance_radiation_terms, dim=(fleet.count, fleet.model.radiation_terms), device=device,
              inputs=[simulator.radiation, fleet.model.hull_type, fleet.state.velocity, fleet.state.orientation,
                      fleet.state.wave_velocity, fleet.state.status],
              outputs=[fleet.state.radiation_state, fleet.state.radiation_output])
    output = fleet.state.radiation_output.numpy().astype(np.float64)
    term = database.radiation[0]
    _, gamma = zero_order_hold(term.a, term.b, substep)
    assert abs(output[0]) < 1e-6 * abs(term.c @ gamma * rise)
    assert abs(output[1] - term.c @ gamma * rise) < 1e-4 * abs(term.c @ gamma * rise)


def test_hulls_without_a_database_sail_as_alone_beside_hulls_with_one(device, rng):
    """A fleet of a hull type with a database and one without: the hull without one moves bit for bit as it does
    in a fleet of its own (the heading frame touches only the database's path)."""
    hull = ow.Hull.box(2.0, 1.0, 0.6)
    plain = ow.BoatType(hull=hull, mass=400.0, added_mass=np.diag([10.0, 60.0, 200.0, 5.0, 30.0, 20.0]),
                        linear_damping=(5.0, 20.0, 40.0, 10.0, 10.0, 10.0))
    with_database = ow.BoatType(hull=hull, mass=400.0, seakeeping=heave_database(rng))
    orientation = quaternion_from_roll_pitch_yaw([[0.4, -0.1, 0.7]])[0]
    velocity = [0.8, 0.3, -0.1, 0.5, -0.2, 0.3]
    states = []
    for boats in ([plain], [plain, with_database]):
        fleet = ow.Fleet(boats, types=list(range(len(boats))), device=device)
        fleet.reset(position=[[20.0 * i, 0.0, 0.05] for i in range(len(boats))], orientation=orientation,
                    velocity=velocity)
        simulator = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(dt=0.01, substeps=2))
        for _ in range(60):
            simulator.step()
        state = fleet.numpy()
        states.append(np.concatenate([state[k][0] for k in ("position", "orientation", "velocity")]))
    assert np.abs(states[0][7:]).max() > 0.0
    np.testing.assert_array_equal(states[0], states[1])
