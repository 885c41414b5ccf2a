"""Water currents against independent numbers: the tide's formula, the depth profile's power law and linear
shear, a hull drifting with a stream, a towed hull in a head current, the beam-on drag of a sheared current on a
box, the log against the GNSS, zero current bit for bit the still water's, resets, validation and the tasks'
seeded draws."""

import dataclasses
import math

import numpy as np
import pytest
import warp as wp

import ocean_warp as ow
from ocean_warp.current import no_current
from ocean_warp.eboat import EBoatConfig, EBoatSimulator, EBoatSimulatorConfig
from ocean_warp.envs import SailingEnv, StartConfig, WaypointConfig
from ocean_warp.envs.registration import TASK_IDS, make_task_config
from ocean_warp.kernels.water_current import CurrentField, current_at, with_current_shift
from tests.hull_setups import calm_ocean, quaternion_about, rotation_matrix

RHO, G = 1025.0, 9.81


def tide(config: ow.CurrentConfig, time):
    """(..., 3) surface current [m/s, world] of ``config`` at ``time`` [s], written out again for the tests."""
    magnitude = config.speed + config.tidal_amplitude * np.cos(2 * np.pi * np.asarray(time) / config.tidal_period
                                                               + config.tidal_phase)
    direction = np.array([math.cos(config.direction), math.sin(config.direction), 0.0])
    return magnitude[..., None] * direction


def random_tide(rng) -> ow.CurrentConfig:
    return ow.CurrentConfig(speed=float(rng.uniform(0.0, 1.0)), direction=float(rng.uniform(-math.pi, math.pi)),
                            tidal_amplitude=float(rng.uniform(0.1, 1.5)), tidal_period=float(rng.uniform(5.0, 50.0)),
                            tidal_phase=float(rng.uniform(-math.pi, math.pi)))


# --- the current itself ---------------------------------------------------------------------------------------
def test_tide_follows_its_formula_at_sampled_times(device, rng):
    config = random_tide(rng)
    current = ow.Current(config, 3, device=device)
    clock = wp.zeros(1, dtype=wp.float64, device=device)
    current.follow(clock)
    for time in rng.uniform(0.0, 5 * config.tidal_period, 12):
        clock.assign(np.array([time]))
        current.update()
        np.testing.assert_allclose(current.state.velocity.numpy(), np.tile(tide(config, time), (3, 1)), atol=2e-6)
    # At a whole number of days (float64 time), the M2 tide is still read to float32's precision.
    long = ow.CurrentConfig(speed=0.3, tidal_amplitude=1.0)
    current = ow.Current(long, 1, device=device)
    clock.assign(np.array([86400.0 * 30 + 1234.5]))
    current.follow(clock)
    np.testing.assert_allclose(current.state.velocity.numpy()[0], tide(long, 86400.0 * 30 + 1234.5), atol=2e-6)


def test_the_simulator_moves_the_tide_with_its_clock(device, rng):
    """A captured step replays the tide's update from the clock, before the hull pass of every substep: after
    n steps the surface current is the one of the last substep's start."""
    config = random_tide(rng)
    fleet = ow.Fleet(ow.BoatType(hull=ow.Hull.box(1.0, 0.5, 0.4), mass=50.0), 1, device=device)
    fleet.reset(position=[0.0, 0.0, 100.0])  # in the air: only the clock matters here
    fleet.tensors.wrench_world[:] = fleet.tensors.wrench_world.new_tensor([0, 0, 50.0 * G, 0, 0, 0])
    current = ow.Current(config, 1, device=device)
    sim = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(dt=0.1, substeps=3, max_altitude=1e4),
                       current=current)
    for steps in (1, 7, 30):
        while round(sim.time / 0.1) < steps:
            sim.step()
        last_substep = sim.time - 0.1 / 3
        np.testing.assert_allclose(current.state.velocity.numpy()[0], tide(config, last_substep), atol=2e-6)


def _profile(depth, exponent, height):
    """u(z) / U of the power law, written out again."""
    height = np.asarray(height, dtype=np.float64)
    if depth == 0.0:
        return np.ones_like(height)
    inside = np.clip(1.0 + height / depth, 0.0, None)
    return np.where(height >= 0.0, 1.0, np.where(height <= -depth, 0.0, inside ** exponent))


@wp.kernel
def _current_at_heights(field: CurrentField, heights: wp.array(dtype=float), rotation: wp.quat,
                        out: wp.array(dtype=wp.vec3), shifted: wp.array(dtype=wp.vec3)):
    i = wp.tid()
    out[i] = current_at(field, 0, heights[i])
    # the flow at the surface (1, 2, 3 in the body frame) moved down to heights[i]
    shifted[i] = with_current_shift(wp.vec3(1.0, 2.0, 3.0), field, 0, rotation, 0.0, heights[i])


@pytest.mark.parametrize("exponent", [1.0 / 7.0, 1.0])
def test_depth_profile_is_the_power_law_or_linear_shear(device, rng, exponent):
    depth = float(rng.uniform(1.0, 20.0))
    config = ow.CurrentConfig(speed=float(rng.uniform(0.2, 2.0)), direction=float(rng.uniform(-3, 3)),
                              profile_depth=depth, profile_exponent=exponent)
    current = ow.Current(config, 1, device=device)
    heights = rng.uniform(-1.5 * depth, 0.5, 200)
    # Within a thousandth of D of the bottom, float32's 1 + z / D loses digits that the 7th root magnifies.
    heights = np.concatenate([heights[np.abs(heights + depth) > 1e-3 * depth], [0.0, -depth, 1.0, -2 * depth]])
    surface = tide(config, 0.0)
    yaw = float(rng.uniform(-math.pi, math.pi))
    q = quaternion_about([0, 0, 1], yaw)
    out = wp.zeros(len(heights), dtype=wp.vec3, device=device)
    shifted = wp.zeros(len(heights), dtype=wp.vec3, device=device)
    wp.launch(_current_at_heights, dim=len(heights), device=device,
              inputs=[current.field, wp.array(heights.astype(np.float32), dtype=float, device=device),
                      wp.quat(*q.astype(np.float32)), out, shifted])
    factor = _profile(float(np.float32(depth)), exponent, heights.astype(np.float32))  # the kernel's float32 D
    np.testing.assert_allclose(out.numpy(), factor[:, None] * surface, rtol=2e-5, atol=2e-6)
    # Moving the flow from the surface down: the current's change rotated into the body frame.
    change = (factor - 1.0)[:, None] * (surface @ rotation_matrix(q))  # world -> body: R^T v = v R
    np.testing.assert_allclose(shifted.numpy(), np.array([1.0, 2.0, 3.0]) + change, rtol=2e-5, atol=2e-6)
    # Uniform with depth (no profile): the same current everywhere, and no shift.
    uniform = ow.Current(dataclasses.replace(config, profile_depth=0.0), 1, device=device)
    wp.launch(_current_at_heights, dim=len(heights), device=device,
              inputs=[uniform.field, wp.array(heights.astype(np.float32), dtype=float, device=device),
                      wp.quat(*q.astype(np.float32)), out, shifted])
    np.testing.assert_allclose(out.numpy(), np.tile(surface, (len(heights), 1)), atol=2e-6)
    np.testing.assert_array_equal(shifted.numpy(), np.tile([1.0, 2.0, 3.0], (len(heights), 1)))
    # Still water (a field without rows): zero.
    wp.launch(_current_at_heights, dim=len(heights), device=device,
              inputs=[no_current(device), wp.array(heights.astype(np.float32), dtype=float, device=device),
                      wp.quat(*q.astype(np.float32)), out, shifted])
    np.testing.assert_array_equal(out.numpy(), 0.0)


# --- what the hull feels ------------------------------------------------------------------------------------------
def floating_box(length=2.0, beam=1.0, height=0.5, draft=0.15, **fields) -> ow.BoatType:
    return ow.BoatType(hull=ow.Hull.box(length, beam, height), mass=RHO * length * beam * draft, **fields)


@pytest.mark.parametrize("profile_depth", [0.0, 0.6])
def test_beam_on_drag_of_a_sheared_current_on_a_box(device, rng, profile_depth):
    """With linear pressure drag and suction only (falloff 1, no friction), a box held beam-on to a current feels
    F_y = (C_PD1 + C_SD1) / v_r L int_{-T}^0 u(z) dz: U L T uniform, U L (T - T^2 / 2D) in a linear shear (exact
    on a mesh whose vertices lie on the waterline, as the box's midpoints do when its centre is there)."""
    length, beam, height = rng.uniform(1.0, 3.0), rng.uniform(0.5, 1.5), 0.6
    draft = height / 2
    hydro = ow.HydrodynamicsConfig(reference_speed=float(rng.uniform(0.5, 2.0)),
                                   pressure_drag_linear=float(rng.uniform(50, 200)), pressure_drag_quadratic=0.0,
                                   pressure_drag_falloff=1.0, suction_linear=float(rng.uniform(20, 100)),
                                   suction_quadratic=0.0, suction_falloff=1.0, skin_friction=False)
    boat = ow.BoatType(hull=ow.Hull.box(length, beam, height, subdivisions=1), mass=RHO * length * beam * draft)
    fleet = ow.Fleet(boat, 1, device=device)
    yaw = float(rng.uniform(-math.pi, math.pi))
    fleet.reset(position=[float(rng.uniform(-20, 20)), float(rng.uniform(-20, 20)), 0.0],
                orientation=quaternion_about([0, 0, 1], yaw))
    speed = float(rng.uniform(0.2, 1.5))
    config = ow.CurrentConfig(speed=speed, direction=yaw + math.pi / 2, profile_depth=profile_depth,
                              profile_exponent=1.0)  # toward the box's port side
    sim = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(hydrodynamics=hydro),
                       current=ow.Current(config, 1, device=device))
    sim.compute_hull_wrenches()
    wrench = fleet.numpy()["hydro_wrench"][0]
    depth_integral = draft if profile_depth == 0.0 else draft - draft**2 / (2 * profile_depth)
    expected = (hydro.pressure_drag_linear + hydro.suction_linear) / hydro.reference_speed * speed * length \
        * depth_integral
    assert wrench[1] == pytest.approx(expected, rel=2e-4)
    assert abs(wrench[0]) < 1e-4 * expected  # nothing along the hull
    np.testing.assert_allclose(fleet.state.water_velocity.numpy()[0], [0.0, speed, 0.0], atol=2e-6)


def test_a_drifting_hull_moves_with_the_stream(device, rng):
    """A box left alone in still water, no sail, no propeller: the hull's drag and its damping act on the
    velocity through the water, so it accelerates until it moves with the current: speed over the ground the
    current's, in its direction, speed through the water zero."""
    speed, direction = float(rng.uniform(0.2, 0.8)), float(rng.uniform(-math.pi, math.pi))
    boat = floating_box(linear_damping=[40.0, 40.0, 0.0, 0.0, 0.0, 0.0])
    fleet = ow.Fleet(boat, 1, device=device)
    fleet.reset(position=[0.0, 0.0, 0.25 - 0.15])  # at its equilibrium
    current = ow.Current(ow.CurrentConfig(speed=speed, direction=direction), 1, device=device)
    sim = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(dt=0.05, substeps=4), current=current)
    world = []
    for _ in range(1200):  # 60 s
        sim.step()
        state = fleet.numpy()
        world.append(rotation_matrix(state["orientation"][0]) @ state["velocity"][0, :3])
    world = np.array(world)
    assert np.linalg.norm(world[20, :2]) < 0.8 * speed  # it started at rest: the drift builds up
    np.testing.assert_allclose(world[-1, :2], [speed * math.cos(direction), speed * math.sin(direction)], atol=2e-3)
    through_water = fleet.numpy()["velocity"][0, :3] - fleet.state.water_velocity.numpy()[0]
    assert np.linalg.norm(through_water[:2]) < 2e-3
    assert np.all(fleet.numpy()["status"] == 0)


def test_a_towed_hull_feels_the_waters_speed_not_the_grounds(device, rng):
    """Two boxes towed ahead by the same constant force, one in still water, one in a head current of c: both
    settle at the same speed through the water, so the second's speed over the ground is the first's minus c."""
    c = float(rng.uniform(0.2, 0.6))
    push = float(rng.uniform(30.0, 80.0))
    boat = floating_box(linear_damping=[20.0, 20.0, 0.0, 0.0, 0.0, 0.0], quadratic_damping=[30.0, 0, 0, 0, 0, 0])
    fleet = ow.Fleet(boat, 2, device=device)
    fleet.reset(position=[[0.0, 0.0, 0.1], [0.0, 10.0, 0.1]])
    fleet.tensors.wrench_body[:] = fleet.tensors.wrench_body.new_tensor([push, 0, 0, 0, 0, 0])
    current = ow.Current(ow.CurrentConfig(), 2, device=device)
    current.set([1], speed=c, direction=math.pi)  # boat 1 heads into it
    sim = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(dt=0.05, substeps=4), current=current)
    for _ in range(1600):  # 80 s
        sim.step()
    state = fleet.numpy()
    over_ground = np.array([rotation_matrix(q) @ v[:3] for q, v in zip(state["orientation"], state["velocity"])])
    through_water = state["velocity"][:, :3] - fleet.state.water_velocity.numpy()
    still_speed = over_ground[0, 0]
    assert still_speed > 0.2  # under way
    assert over_ground[1, 0] == pytest.approx(still_speed - c, abs=2e-3)
    assert through_water[1, 0] == pytest.approx(through_water[0, 0], abs=2e-3)
    assert through_water[0, 0] == pytest.approx(still_speed, abs=1e-5)  # still water: the two are one
    np.testing.assert_allclose(over_ground[:, 1], 0.0, atol=1e-3)


def test_the_log_reads_through_the_water_and_the_gnss_over_the_ground(device, rng):
    """An E-Boat left alone (sheeted in, no propeller) in a current, the air moving with the water: it drifts with
    both, so the GNSS velocity (over the ground) becomes the current and the log (speed through the water) zero.
    Its surge is the slowest to settle (time constant about 30 s: 158 kg on 5 N s/m): 200 s."""
    speed, direction = float(rng.uniform(0.3, 0.8)), float(rng.uniform(-math.pi, math.pi))
    config = EBoatSimulatorConfig(boat=EBoatConfig(hydrostatics="points"),
                                  wind=ow.WindConfig(speed=speed, direction=direction),
                                  current=ow.CurrentConfig(speed=speed, direction=direction),
                                  sensors=ow.SensorConfig.noise_free())
    sim = EBoatSimulator(config, 1, device=device)
    sim.reset(position=[0.0, 0.0, sim.eboat.rest_height(device, config.water)], heading=float(rng.uniform(-3, 3)))
    sim.step()
    first = sim.state.truth.numpy()[0].copy()
    for _ in range(3999):
        sim.step()
    last = sim.state.truth.numpy()[0]
    np.testing.assert_allclose(last[3:5], [speed * math.cos(direction), speed * math.sin(direction)], atol=5e-3)
    assert abs(last[15]) < 5e-3
    # At the start the boat lay still over the ground while the water ran past it: the log read the current's
    # part along the bow (less than it, backwards), the GNSS almost nothing.
    assert first[15] == pytest.approx(-speed * math.cos(direction - first[12]), abs=0.05)
    assert np.hypot(*first[3:5]) < 0.1


# --- still water is still water -------------------------------------------------------------------------------
def _box_run(device, current, hull_pressure, steps=60):
    boat = floating_box(linear_damping=[20.0, 20.0, 30.0, 5.0, 5.0, 5.0])
    fleet = ow.Fleet(boat, 2, device=device)
    fleet.reset(position=[[0.0, 0.0, 0.12], [3.0, 1.0, 0.05]], orientation=[quaternion_about([1, 2, 3], 0.1),
                                                                              quaternion_about([0, 0, 1], 1.0)],
                velocity=[[0.5, 0.1, 0.0, 0.0, 0.0, 0.2], [-0.2, 0.3, 0.1, 0.1, 0.0, 0.0]])
    ocean = ow.Ocean(ow.OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.5, peak_period=4.0),
                     device=device)
    config = ow.SimulatorConfig(dt=0.02, substeps=2, hull_pressure=hull_pressure)
    sim = ow.Simulator(ocean, fleet, config, current=None if current is None else ow.Current(current, 2, device=device))
    trajectory = []
    for _ in range(steps):
        sim.step()
        state = fleet.numpy()
        trajectory.append(np.concatenate([state["position"].ravel(), state["orientation"].ravel(),
                                          state["velocity"].ravel(), fleet.state.water_velocity.numpy().ravel()]))
    return np.array(trajectory)


@pytest.mark.parametrize("hull_pressure", [True, False])
def test_zero_current_is_the_still_water_trajectory_bit_for_bit(device, hull_pressure):
    still = _box_run(device, None, hull_pressure)
    for zero in (ow.CurrentConfig(), ow.CurrentConfig(direction=1.0, profile_depth=3.0)):
        np.testing.assert_array_equal(_box_run(device, zero, hull_pressure), still)
    assert not np.array_equal(_box_run(device, ow.CurrentConfig(speed=0.05), hull_pressure), still)


def test_an_eboat_in_zero_current_sails_as_without_one(device):
    """The E-Boat's rig (keel and rudder at their depth) and hull with a zero current and with none at all (the
    simulator's current taken out before its first step, as a Simulator without one has it): the same, bit for
    bit; with a current, not."""
    config = EBoatSimulatorConfig(boat=EBoatConfig(hydrostatics="points"), ocean=ow.OceanConfig(
        tile_size=64.0, resolution=16, significant_wave_height=0.4, peak_period=3.0),
        wind=ow.WindConfig(speed=6.0, direction=2.0, gust_speed_std=1.0, gust_direction_std=0.1),
        current=ow.CurrentConfig(profile_depth=2.0))

    def run(without_current, current_speed=0.0):
        sim = EBoatSimulator(config, 2, device=device)
        if without_current:
            sim.simulator.current, sim.simulator.current_field = None, no_current(sim.device)
        sim.reset(heading=[0.3, -2.0], sheet=0.6, current_speed=current_speed, current_direction=1.0)
        sim.tensors.control.rudder[:] = 0.2
        sim.tensors.control.propeller[:] = 2
        states = []
        for _ in range(40):
            sim.step()
            states.append(np.concatenate([sim.state.position.numpy().ravel(), sim.state.velocity.numpy().ravel(),
                                          sim.state.truth.numpy().ravel()]))
        return np.array(states)

    reference = run(True)
    np.testing.assert_array_equal(run(False), reference)
    assert not np.array_equal(run(False, current_speed=0.1), reference)


# --- resets, validation, tasks ----------------------------------------------------------------------------------
def test_reset_sets_the_chosen_environments_current_at_the_simulators_time(device, rng):
    config = EBoatSimulatorConfig(boat=EBoatConfig(hydrostatics="points"),
                                  current=ow.CurrentConfig(speed=0.2, tidal_amplitude=0.5, tidal_period=7.0))
    sim = EBoatSimulator(config, 5, device=device)
    for _ in range(13):
        sim.step()
    before = sim.state.current_velocity.numpy().copy()
    chosen = np.array([1, 3])
    speeds, directions = rng.uniform(0.0, 1.0, 2), rng.uniform(-3.0, 3.0, 2)
    sim.reset(chosen, current_speed=speeds, current_direction=directions)
    after = sim.state.current_velocity.numpy()
    others = [0, 2, 4]
    np.testing.assert_array_equal(after[others], before[others])
    for k, boat in enumerate(chosen):
        expected = tide(dataclasses.replace(config.current, speed=speeds[k], direction=directions[k]), sim.time)
        np.testing.assert_allclose(after[boat], expected, atol=2e-6)
    np.testing.assert_allclose(sim.state.current_speed.numpy()[chosen], speeds, rtol=1e-6)
    sim.reset(chosen)  # without current_*: kept
    np.testing.assert_allclose(sim.state.current_speed.numpy()[chosen], speeds, rtol=1e-6)


@pytest.mark.parametrize("fields,message", [
    ({"speed": -0.1}, r"CurrentConfig\.speed must be >= 0 \[m/s\], got -0\.1"),
    ({"direction": math.nan}, r"CurrentConfig\.direction must be finite"),
    ({"tidal_amplitude": -1.0}, r"CurrentConfig\.tidal_amplitude must be >= 0"),
    ({"tidal_period": 0.0}, r"CurrentConfig\.tidal_period must be > 0 \[s\]"),
    ({"tidal_phase": math.inf}, r"CurrentConfig\.tidal_phase must be finite"),
    ({"profile_depth": -2.0}, r"CurrentConfig\.profile_depth must be >= 0 \[m\]"),
    ({"profile_exponent": 0.0}, r"CurrentConfig\.profile_exponent must be in \(0, 1\], got 0\.0"),
    ({"profile_exponent": 1.5}, r"CurrentConfig\.profile_exponent must be in \(0, 1\], got 1\.5"),
])
def test_bad_current_config_names_the_field(fields, message):
    with pytest.raises(ValueError, match=message):
        ow.CurrentConfig(**fields)


def test_bad_current_input_is_refused_in_one_line():
    with pytest.raises(ValueError, match=r"EBoatSimulatorConfig\.current must be a CurrentConfig"):
        EBoatSimulatorConfig(current=0.5)
    with pytest.raises(ValueError, match=r"StartConfig\.current_speed must have low <= high"):
        StartConfig(current_speed=(1.0, 0.5))
    with pytest.raises(ValueError, match=r"StartConfig\.current_speed must be in \[0\.0, 5\.0\]"):
        StartConfig(current_speed=(0.0, 6.0))
    with pytest.raises(ValueError, match=r"StartConfig\.current_direction_deg must be in \[-360\.0, 360\.0\]"):
        StartConfig(current_direction_deg=(0.0, 400.0))
    current = ow.Current(None, 3, device="cpu")
    with pytest.raises(ValueError, match=r"Current\.set: speed must be >= 0"):
        current.set(speed=-1.0, direction=0.0)
    with pytest.raises(ValueError, match=r"Current\.set\.direction holds NaN"):
        current.set(speed=1.0, direction=math.nan)
    with pytest.raises(ValueError, match=r"Current\.set\.envs: indices must lie in \[0, 2\]"):
        current.set([3], speed=1.0, direction=0.0)
    with pytest.raises(ValueError, match=r"EBoatSimulator\.reset\.current_speed must be >= 0"):
        EBoatSimulator(EBoatSimulatorConfig(boat=EBoatConfig(hydrostatics="points")), 1, device="cpu").reset(
            current_speed=-0.5)
    fleet = ow.Fleet(floating_box(), 2, device="cpu")
    with pytest.raises(ValueError, match="the current holds 3 environments on cpu, the fleet 2 boats on cpu"):
        ow.Simulator(calm_ocean("cpu"), fleet, current=current)
    with pytest.raises(ValueError, match=r"Simulator: current must be an ocean_warp\.Current or None"):
        ow.Simulator(calm_ocean("cpu"), fleet, current=ow.CurrentConfig())


def test_no_shipped_task_has_a_current():
    """No registered task sails in a current: the E-Boat's draw none, VRX's a range of zero (VRX has none)."""
    for task_id in TASK_IDS:
        task = make_task_config(task_id)
        assert task.start.current_speed in (None, (0.0, 0.0)) and task.simulator.current.still, task_id


def _start_rows(env) -> dict:
    start = env.simulator.start
    return {name: getattr(start, name).numpy().copy() for name in start.names()}


def test_tasks_draw_the_current_per_episode_in_range_and_seeded(rng):
    base = dataclasses.replace(WaypointConfig(), simulator=dataclasses.replace(
        WaypointConfig().simulator, ocean=ow.OceanConfig(tile_size=256.0, resolution=16, significant_wave_height=0.0)))
    low, high = sorted(rng.uniform(0.0, 2.0, 2))
    drawn = dataclasses.replace(base, start=dataclasses.replace(base.start, current_speed=(low, high),
                                                                current_direction_deg=(-90.0, 45.0)))
    seed = int(rng.integers(2**31))
    envs = 64
    env = SailingEnv(drawn, envs, device="cpu", seed=seed)
    speeds, directions = env.simulator.state.current_speed.numpy(), env.simulator.state.current_direction.numpy()
    assert np.all((speeds >= low - 1e-6) & (speeds <= high + 1e-6))
    assert np.all((directions >= math.radians(-90.0) - 1e-6) & (directions <= math.radians(45.0) + 1e-6))
    # spread over the ranges (64 uniform draws leave no more than a quarter of either range empty at each end)
    assert speeds.min() < low + 0.25 * (high - low) and speeds.max() > high - 0.25 * (high - low)
    assert directions.min() < math.radians(-90.0 + 0.25 * 135.0) and directions.max() > math.radians(45 - 0.25 * 135)
    velocity = env.simulator.state.current_velocity.numpy()
    np.testing.assert_allclose(velocity[:, :2], speeds[:, None] * np.column_stack([np.cos(directions),
                                                                                   np.sin(directions)]), atol=2e-6)
    rows = _start_rows(env)
    again = _start_rows(SailingEnv(drawn, envs, device="cpu", seed=seed))
    other = _start_rows(SailingEnv(drawn, envs, device="cpu", seed=seed + 1))
    without = _start_rows(SailingEnv(base, envs, device="cpu", seed=seed))
    for name in rows:
        np.testing.assert_array_equal(again[name], rows[name], err_msg=name)
        if not name.startswith("current"):  # the current draws from a stream of its own
            np.testing.assert_array_equal(without[name], rows[name], err_msg=name)
    assert not np.array_equal(other["current_speed"], rows["current_speed"])
    np.testing.assert_array_equal(without["current_speed"], 0.0)
    # Without a range, every episode starts with the simulator config's current.
    configured = dataclasses.replace(base, simulator=dataclasses.replace(
        base.simulator, current=ow.CurrentConfig(speed=0.4, direction=-1.0)))
    env = SailingEnv(configured, 4, device="cpu", seed=seed)
    np.testing.assert_allclose(env.simulator.state.current_speed.numpy(), 0.4, rtol=1e-6)
    np.testing.assert_allclose(env.simulator.state.current_direction.numpy(), -1.0, rtol=1e-6)
