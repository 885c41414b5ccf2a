"""The fleet's state on the device: torch views, resets of chosen boats, status flags, graph replay."""

import math

import numpy as np
import pytest
import torch

import ocean_warp as ow
from ocean_warp import BoatStatus
from tests.hull_setups import calm_ocean, quaternion_about, random_rotations


def floating_box_fleet(device, count):
    boat = ow.BoatType.floating_solid(ow.Hull.box(2.0, 1.0, 0.6), draft_fraction=0.4,
                                      linear_damping=[100, 100, 2000, 200, 200, 100])
    return ow.Fleet(boat, count, device=device)


def test_torch_views_share_memory_with_the_simulator(device, rng):
    fleet = floating_box_fleet(device, 4)
    simulator = ow.Simulator(calm_ocean(device), fleet)
    views = fleet.tensors
    assert views.position.shape == (4, 3) and views.orientation.shape == (4, 4) and views.velocity.shape == (4, 6)
    assert views is fleet.tensors, "views are bound once"
    heights = torch.as_tensor(rng.uniform(-0.5, 0.5, size=4), dtype=torch.float32, device=views.position.device)
    views.position[:, 2] = heights  # written through torch, read by the kernels
    np.testing.assert_allclose(fleet.numpy()["position"][:, 2], heights.cpu().numpy())
    simulator.step()
    np.testing.assert_array_equal(views.position.cpu().numpy(), fleet.numpy()["position"])
    assert not torch.equal(views.position[:, 2].cpu(), heights.cpu()), "the step moved the boats"


def test_reset_changes_only_the_chosen_boats(device, rng):
    fleet = floating_box_fleet(device, 6)
    fleet.reset(position=rng.uniform(-5, 5, size=(6, 3)), velocity=rng.uniform(-1, 1, size=(6, 6)))
    before = fleet.numpy()
    chosen = torch.tensor([1, 4])
    positions = rng.uniform(-5, 5, size=(2, 3))
    orientations = random_rotations(rng, 2, math.pi)
    fleet.reset(chosen, position=positions, orientation=orientations)
    after = fleet.numpy()
    np.testing.assert_allclose(after["position"][[1, 4]], positions, rtol=1e-6)
    np.testing.assert_allclose(np.abs(np.sum(after["orientation"][[1, 4]] * orientations, axis=1)), 1.0, rtol=1e-6)
    np.testing.assert_array_equal(after["velocity"][[1, 4]], 0.0)
    others = [0, 2, 3, 5]
    np.testing.assert_array_equal(after["position"][others], before["position"][others])
    np.testing.assert_array_equal(after["velocity"][others], before["velocity"][others])


def test_bad_state_is_flagged_and_frozen_not_carried_on(device):
    fleet = floating_box_fleet(device, 5)
    upside_down = quaternion_about([1.0, 0.0, 0.0], math.pi)
    fleet.reset(position=[[0, 0, 0], [0, 10, 0], [0, 20, 0], [0, 30, 35.0], [0, 40, -70.0]],
                orientation=[[0, 0, 0, 1], [0, 0, 0, 1], upside_down, [0, 0, 0, 1], [0, 0, 0, 1]])
    fleet.tensors.velocity[1, 3] = float("nan")
    simulator = ow.Simulator(calm_ocean(device, tile_size=256.0), fleet, ow.SimulatorConfig(max_altitude=20.0,
                                                                                             max_depth=50.0))
    frozen = fleet.numpy()["position"][1].copy()
    for _ in range(3):
        simulator.step()
    state = fleet.numpy()
    assert state["status"][0] == 0
    assert state["status"][1] & BoatStatus.NONFINITE
    np.testing.assert_array_equal(state["position"][1], frozen)
    assert np.all(np.isfinite(state["position"])) and np.all(np.isfinite(state["velocity"]))
    assert state["status"][2] & BoatStatus.CAPSIZED
    assert state["status"][3] & BoatStatus.FLYING
    assert state["status"][4] & BoatStatus.SUNK
    fleet.reset([1, 2, 3, 4], position=[0.0, 0.0, 0.0])
    assert np.all(fleet.numpy()["status"] == 0)


def test_captured_step_replays_the_eager_step(device, rng):
    ocean_config = ow.OceanConfig(resolution=64, tile_size=100.0, significant_wave_height=1.5, peak_period=5.0,
                                  seed=int(rng.integers(2**31)))
    start = np.column_stack([rng.uniform(0, 100, size=(8, 2)), rng.uniform(-0.3, 0.1, size=8)])
    runs = []
    for capture in (False, True):
        fleet = floating_box_fleet(device, 8)
        fleet.reset(position=start)
        simulator = ow.Simulator(ow.Ocean(ocean_config, device=device), fleet,
                                 ow.SimulatorConfig(capture_graph=capture))
        for _ in range(20):
            simulator.step()
        runs.append((fleet.numpy(), simulator.time))
    np.testing.assert_allclose(runs[0][0]["position"], runs[1][0]["position"], rtol=1e-5, atol=1e-6)
    assert runs[0][1] == pytest.approx(runs[1][1]) == pytest.approx(20 * 0.01)


def test_mixed_hull_types_float_at_their_own_drafts(device, rng):
    box = ow.BoatType.floating_solid(ow.Hull.box(2.0, 1.0, 0.6), draft_fraction=0.3,
                                     linear_damping=[0, 0, 3000, 300, 300, 0])
    sphere = ow.BoatType.floating_solid(ow.Hull.sphere(0.5, subdivisions=3), draft_fraction=0.5,
                                        linear_damping=[0, 0, 1500, 50, 50, 0])
    fleet = ow.Fleet([box, sphere], types=[0, 1, 1, 0], device=device)
    fleet.reset(position=np.column_stack([np.zeros(4), [0, 10, 20, 30], rng.uniform(-0.2, 0.2, 4)]))
    simulator = ow.Simulator(calm_ocean(device), fleet, ow.SimulatorConfig(dt=0.02))
    for _ in range(800):
        simulator.step()
    z = fleet.numpy()["position"][:, 2]
    np.testing.assert_allclose(z[[0, 3]], 0.3 - 0.3 * 0.6, atol=2e-3)  # box: draft 30 % of its height
    np.testing.assert_allclose(z[[1, 2]], 0.0, atol=5e-3)  # sphere half in


@pytest.mark.parametrize("call,message", [
    (lambda b: ow.Fleet(b, 0), "count must be an integer >= 1"),
    (lambda b: ow.Fleet([b, b], 3), "say which boat has which"),
    (lambda b: ow.Fleet([b], types=[0, 2]), r"types must lie in \[0, 0\]"),
])
def test_bad_fleets_are_refused(call, message):
    boat = ow.BoatType.floating_solid(ow.Hull.box(1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match=message):
        call(boat)


def test_bad_resets_are_refused(device):
    fleet = floating_box_fleet(device, 3)
    with pytest.raises(ValueError, match=r"position must have shape \(2, 3\)"):
        fleet.reset([0, 1], position=np.zeros((3, 3)))
    with pytest.raises(ValueError, match="NaN or infinite"):
        fleet.reset(position=[0.0, np.nan, 0.0])
    with pytest.raises(ValueError, match=r"indices must lie in \[0, 2\]"):
        fleet.reset([3], position=[0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="must not be zero"):
        fleet.reset(position=[0.0, 0.0, 0.0], orientation=[0.0, 0.0, 0.0, 0.0])
