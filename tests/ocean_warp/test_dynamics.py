"""Rigid-body dynamics in water against analytic results: heave period with added mass, energy in free
decay, following a long wave, torque-free motion (Kirchhoff), and the effective mass."""

import math

import numpy as np
import pytest

import ocean_warp as ow
from tests.hull_setups import calm_ocean, rotation_matrix

RHO, G = 1025.0, 9.81
STILL = ow.HydrodynamicsConfig().without_drag()


def heave_record(device, boat, start_height, steps, *, dt=0.01, substeps=4, hydro=STILL, ocean=None):
    """Heave z(t) [m] and its rate of one boat released at rest at ``start_height``."""
    fleet = ow.Fleet(boat, 1, device=device)
    fleet.reset(position=[0.0, 0.0, start_height])
    simulator = ow.Simulator(ocean or calm_ocean(device), fleet,
                             ow.SimulatorConfig(dt=dt, substeps=substeps, hydrodynamics=hydro))
    heights, rates = [], []
    for _ in range(steps):
        simulator.step()
        state = fleet.numpy()
        heights.append(state["position"][0, 2])
        rates.append(state["velocity"][0, 2])
    return np.array(heights, dtype=np.float64), np.array(rates, dtype=np.float64)


def upward_crossings(signal, dt):
    """Times of the upward zero crossings of a sampled signal, linearly interpolated [s]."""
    i = np.flatnonzero((signal[:-1] < 0) & (signal[1:] >= 0))
    return (i + signal[i] / (signal[i] - signal[i + 1])) * dt


def random_heaving_box(rng):
    """A floating box (centre of mass at its centre) that is stable in roll: a box with a negative metacentric
    height heels away, and heave alone then no longer holds its energy (seed 1413955757029078196 drew
    GM = -0.14 m, and the heave energy grew 19 % as it rolled)."""
    while True:
        length, beam, height = rng.uniform(1.0, 4.0), rng.uniform(0.8, 2.0), rng.uniform(0.5, 1.0)
        draft = rng.uniform(0.3, 0.6) * height
        metacentric_height = draft / 2 + beam**2 / (12 * draft) - height / 2  # KB + BM - KG, the narrow axis
        if metacentric_height > 0.05:
            break
    mass = RHO * length * beam * draft
    return length, beam, height, draft, mass


def test_heave_natural_period_with_added_mass(device, rng):
    length, beam, height, draft, mass = random_heaving_box(rng)
    added = rng.uniform(0.2, 1.0) * mass
    boat = ow.BoatType(hull=ow.Hull.box(length, beam, height), mass=mass, added_mass=[0, 0, added, 0, 0, 0])
    equilibrium = 0.5 * height - draft
    dt = 0.01
    heights, _ = heave_record(device, boat, equilibrium + 0.05 * draft, 600, dt=dt)
    crossings = upward_crossings(heights - equilibrium, dt)
    assert len(crossings) >= 3
    measured = np.mean(np.diff(crossings))
    expected = 2 * math.pi * math.sqrt((mass + added) / (RHO * G * length * beam))
    assert measured == pytest.approx(expected, rel=2e-3)


def heave_energy(heights, rates, equilibrium, mass, added, waterplane):
    """Kinetic plus hydrostatic energy of a wall-sided box in heave [J]."""
    return 0.5 * (mass + added) * rates**2 + 0.5 * RHO * G * waterplane * (heights - equilibrium) ** 2


@pytest.mark.parametrize("with_drag", [False, True])
def test_free_decay_never_gains_energy(device, rng, with_drag):
    length, beam, height, draft, mass = random_heaving_box(rng)
    added = rng.uniform(0.0, 0.5) * mass
    damping = 0.0 if not with_drag else rng.uniform(0.02, 0.2) * 2 * math.sqrt(RHO * G * length * beam * mass)
    boat = ow.BoatType(hull=ow.Hull.box(length, beam, height), mass=mass, added_mass=[0, 0, added, 0, 0, 0],
                       linear_damping=[0, 0, damping, 0, 0, 0])
    equilibrium = 0.5 * height - draft
    hydro = ow.HydrodynamicsConfig() if with_drag else STILL
    heights, rates = heave_record(device, boat, equilibrium + rng.uniform(0.05, 0.3) * draft, 800, hydro=hydro)
    energy = heave_energy(heights, rates, equilibrium, mass, added, length * beam)
    # At the turning points all the energy is potential: it must never grow from one to the next.
    turning = np.flatnonzero(np.sign(rates[:-1]) != np.sign(rates[1:]))
    peaks = np.array([0.5 * RHO * G * length * beam * (heights[i] - equilibrium) ** 2 for i in turning])
    assert len(peaks) >= 6
    if with_drag:
        assert np.all(np.diff(peaks) <= 1e-6 * peaks[0])
        assert energy[-1] < 0.5 * energy[0]
    else:  # symplectic Euler: the energy oscillates within the step's error, with no drift
        assert np.all(peaks <= peaks[0] * 1.005)
        assert np.max(energy) <= energy[0] * 1.02


def test_small_box_heaves_with_a_long_wave(device, rng):
    length, beam, height, draft = 1.0, 1.0, 0.5, 0.15
    mass = RHO * length * beam * draft
    wavelength = rng.uniform(25.0, 40.0)
    amplitude = rng.uniform(0.05, 0.2)
    period = math.sqrt(2 * math.pi * wavelength / G)
    ocean = ow.Ocean(ow.OceanConfig(spectrum="regular", tile_size=2 * wavelength, resolution=64, amplitude=amplitude,
                                    period=period), device=device)
    critical = 2 * math.sqrt(RHO * G * length * beam * mass)
    boat = ow.BoatType(hull=ow.Hull.box(length, beam, height, subdivisions=1), mass=mass,
                       linear_damping=[0, 0, 0.3 * critical, 0.3 * critical, 0.3 * critical, 0])
    dt = 0.02
    steps = int(8 * period / dt)
    heights, _ = heave_record(device, boat, 0.5 * height - draft, steps, dt=dt, hydro=ow.HydrodynamicsConfig(),
                              ocean=ocean)
    last_three_periods = heights[-int(3 * period / dt):]
    measured_amplitude = 0.5 * (last_three_periods.max() - last_three_periods.min())
    assert measured_amplitude / amplitude == pytest.approx(1.0, abs=0.05)


def free_body_run(device, boat, nu0, steps, dt):
    """A body high above the water, its weight held by an equal upward force: torque-free motion."""
    fleet = ow.Fleet(boat, 1, device=device)
    fleet.reset(position=[0.0, 0.0, 100.0], velocity=nu0)
    weight = np.zeros(6)
    weight[2] = boat.mass * G
    fleet.tensors.wrench_world[:] = fleet.tensors.wrench_world.new_tensor(weight)
    config = ow.SimulatorConfig(dt=dt, substeps=1, max_altitude=1e4, hydrodynamics=STILL)
    simulator = ow.Simulator(calm_ocean(device), fleet, config)
    states = []
    for _ in range(steps):
        simulator.step()
        states.append(fleet.numpy())
    return states


def test_torque_free_body_conserves_kirchhoff_energy(device, rng):
    """With added mass and an off-centre centre of mass, 1/2 nu^T (M_RB + M_A) nu is an invariant of
    Kirchhoff's equations (for any symmetric M: the impulses below check M itself)."""
    hull = ow.Hull.ellipsoid(*rng.uniform(0.5, 2.0, size=3), subdivisions=1)
    mass = rng.uniform(50, 500)
    boat = ow.BoatType(hull=hull, mass=mass, center_of_mass=rng.uniform(-0.2, 0.2, size=3),
                       added_mass=np.concatenate([rng.uniform(0.1, 1.0, 3) * mass, rng.uniform(0.1, 1.0, 3) * mass]))
    nu0 = np.concatenate([rng.uniform(-1, 1, 3), rng.uniform(-2, 2, 3)])
    states = free_body_run(device, boat, nu0, 2000, dt=0.0025)
    matrix = boat.mass_matrix
    energy = np.array([0.5 * s["velocity"][0] @ matrix @ s["velocity"][0] for s in states])
    # The velocity terms are integrated at the midpoint: the invariant holds to the step's accuracy.
    assert np.abs(energy / energy[0] - 1.0).max() < 1e-3
    assert np.abs(states[-1]["velocity"][0] - nu0).max() > 0.05, "the motion should not be trivial"


def test_torque_free_body_conserves_kirchhoff_impulses(device, rng):
    """Kirchhoff's equations keep the world-frame impulses of a free body constant: P = R (M nu)_v and,
    about a fixed point (here the start), Pi = R (M nu)_w + x x P (x the body origin from that point). With added mass and an off-centre
    centre of mass this checks the coupling blocks of M_RB and the velocity terms, which the energy
    (invariant for any symmetric M) cannot."""
    hull = ow.Hull.ellipsoid(*rng.uniform(0.5, 2.0, size=3), subdivisions=1)
    mass = rng.uniform(50, 500)
    boat = ow.BoatType(hull=hull, mass=mass, center_of_mass=rng.uniform(-0.3, 0.3, size=3),
                       added_mass=np.concatenate([rng.uniform(0.1, 1.0, 3) * mass, rng.uniform(0.1, 1.0, 3) * mass]))
    nu0 = np.concatenate([rng.uniform(-1, 1, 3), rng.uniform(-2, 2, 3)])
    states = free_body_run(device, boat, nu0, 2000, dt=0.0025)

    def impulses(state):
        turn = rotation_matrix(state["orientation"][0])
        body = boat.mass_matrix @ state["velocity"][0].astype(np.float64)
        linear = turn @ body[:3]
        return np.concatenate([linear, turn @ body[3:] + np.cross(np.subtract(state["position"][0], [0.0, 0.0, 100.0]), linear)])

    start = impulses({"orientation": [[0.0, 0.0, 0.0, 1.0]], "velocity": [nu0], "position": [[0.0, 0.0, 100.0]]})
    drift = np.array([impulses(s) - start for s in states])
    # The pose follows the new velocity (first order): over these 5 s the linear impulse drifts by up
    # to 0.2 % and the angular one by up to 4 % (40 random bodies), halving with the step. A sign error
    # in the coupling blocks moves them by 60 % to 400 %.
    assert np.abs(drift[:, :3]).max() < 1e-2 * np.linalg.norm(start[:3])
    assert np.abs(drift[:, 3:]).max() < 0.1 * np.linalg.norm(start[3:])
    assert np.abs(states[-1]["velocity"][0] - nu0).max() > 0.05, "the motion should not be trivial"


def test_external_force_accelerates_the_effective_mass(device, rng):
    hull = ow.Hull.box(2.0, 1.0, 0.5)
    mass, added = rng.uniform(50, 300), rng.uniform(10, 100)
    boat = ow.BoatType(hull=hull, mass=mass, added_mass=[added, 0, 0, 0, 0, 0])
    fleet = ow.Fleet(boat, 1, device=device)
    fleet.reset(position=[0.0, 0.0, 100.0])
    push = rng.uniform(10, 200)
    fleet.tensors.wrench_body[:] = fleet.tensors.wrench_body.new_tensor([push, 0, 0, 0, 0, 0])
    fleet.tensors.wrench_world[:] = fleet.tensors.wrench_world.new_tensor([0, 0, mass * G, 0, 0, 0])
    simulator = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(dt=0.01, max_altitude=1e4,
                                                                            hydrodynamics=STILL))
    for _ in range(100):
        simulator.step()
    surge = fleet.numpy()["velocity"][0, 0]
    assert surge == pytest.approx(push * 1.0 / (mass + added), rel=1e-4)


def numpy_velocity_terms(nu, nu_r, boat):
    """c(nu) = c_RB(nu) + C_A(nu_r) nu_r + D_l nu_r + D_q |nu_r| nu_r, written out again for the test."""
    v, w = nu[:3], nu[3:]
    m, r = boat.mass, boat.center_of_mass
    c_rb = np.concatenate([m * (np.cross(w, v) + np.cross(w, np.cross(w, r))),
                           np.cross(w, boat.inertia_about_origin @ w) + m * np.cross(r, np.cross(w, v))])
    a = boat.added_mass @ nu_r
    c_a = np.concatenate([np.cross(nu_r[3:], a[:3]), np.cross(nu_r[:3], a[:3]) + np.cross(nu_r[3:], a[3:])])
    return c_rb + c_a + boat.linear_damping * nu_r + boat.quadratic_damping * np.abs(nu_r) * nu_r


def test_velocity_terms_and_their_jacobian_match_numpy(device, rng):
    import warp as wp

    from ocean_warp.kernels.spatial import vec6
    from ocean_warp.kernels.rigid_body import mat66, velocity_terms, velocity_terms_jacobian

    @wp.kernel
    def evaluate(nu: wp.array(dtype=vec6), current: wp.array(dtype=wp.vec3), mass: float, r_g: wp.vec3,
                 inertia: wp.mat33, added: mat66, lin: vec6, quad: vec6,
                 terms: wp.array(dtype=vec6), jacobians: wp.array(dtype=mat66)):
        i = wp.tid()
        c = current[i]
        nu_r = nu[i] - vec6(c[0], c[1], c[2], 0.0, 0.0, 0.0)
        terms[i] = velocity_terms(nu[i], nu_r, mass, r_g, inertia, added, lin, quad)
        jacobians[i] = velocity_terms_jacobian(nu[i], nu_r, mass, r_g, inertia, added, lin, quad)

    symmetric = rng.normal(size=(6, 6))
    boat = ow.BoatType(hull=ow.Hull.box(2.0, 1.0, 0.5), mass=float(rng.uniform(50, 300)),
                       center_of_mass=rng.uniform(-0.3, 0.3, 3),
                       added_mass=20 * (symmetric @ symmetric.T) + 50 * np.eye(6),
                       linear_damping=rng.uniform(0, 100, 6), quadratic_damping=rng.uniform(0, 100, 6))
    count = 16
    nu = rng.uniform(-2, 2, size=(count, 6))
    current = rng.uniform(-1, 1, size=(count, 3))
    terms = wp.zeros(count, dtype=vec6, device=device)
    jacobians = wp.zeros(count, dtype=mat66, device=device)
    wp.launch(evaluate, dim=count, device=device, inputs=[
        wp.array(nu, dtype=vec6, device=device), wp.array(current, dtype=wp.vec3, device=device), boat.mass,
        wp.vec3(*boat.center_of_mass), wp.mat33(*boat.inertia_about_origin.ravel()),
        mat66(*boat.added_mass.ravel()), vec6(*boat.linear_damping), vec6(*boat.quadratic_damping)],
        outputs=[terms, jacobians])
    for i in range(count):
        shift = np.concatenate([current[i], np.zeros(3)])
        expected = numpy_velocity_terms(nu[i], nu[i] - shift, boat)
        np.testing.assert_allclose(terms.numpy()[i], expected, rtol=1e-4, atol=1e-3)
        numeric = np.empty((6, 6))
        for j in range(6):
            step = np.zeros(6)
            step[j] = 1e-6
            numeric[:, j] = (numpy_velocity_terms(nu[i] + step, nu[i] + step - shift, boat)
                             - numpy_velocity_terms(nu[i] - step, nu[i] - step - shift, boat)) / 2e-6
        np.testing.assert_allclose(jacobians.numpy()[i], numeric, rtol=1e-4, atol=1e-2)


def test_surge_damping_is_stronger_astern(device, rng):
    """The original twin's damping is 1.3 times larger going astern: decelerations ahead and astern
    from the same speed differ by exactly that factor."""
    linear, quadratic = rng.uniform(5, 50), rng.uniform(5, 50)
    boat = ow.BoatType(hull=ow.Hull.box(2.0, 1.0, 0.5), mass=100.0, linear_damping=[linear, 0, 0, 0, 0, 0],
                       quadratic_damping=[quadratic, 0, 0, 0, 0, 0], astern_surge_factor=1.3)
    fleet = ow.Fleet(boat, 2, device=device)
    speed = rng.uniform(0.5, 2.0)
    fleet.reset(position=[[0.0, 0.0, 100.0], [0.0, 10.0, 100.0]], velocity=[[speed, 0, 0, 0, 0, 0], [-speed, 0, 0, 0, 0, 0]])
    fleet.tensors.wrench_world[:] = fleet.tensors.wrench_world.new_tensor([0, 0, boat.mass * G, 0, 0, 0])
    simulator = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(dt=1e-3, substeps=1, max_altitude=1e4,
                                                                            hydrodynamics=STILL))
    simulator.step()
    change = fleet.numpy()["velocity"][:, 0] - [speed, -speed]
    assert -change[1] / change[0] == pytest.approx(1.3, rel=1e-3)
    # Ahead, m du/dt = -(d_l u + d_q u^2): over 1 ms the speed changes by that times dt / m (to 1e-2).
    assert change[0] == pytest.approx(-1e-3 * (linear * speed + quadratic * speed**2) / boat.mass, rel=1e-2)
