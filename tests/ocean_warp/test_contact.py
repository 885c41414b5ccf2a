"""Contact against analytic cases: the capsule's overlap and force by hand, a boat driven into a pile stops
outside it, two boats meeting head-on are flagged (and, with a stiffness, kept apart)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import torch

import ocean_warp as ow
from ocean_warp.contact import Contact, ContactConfig, boat_capsule
from ocean_warp.eboat import EBoatSimulator, EBoatSimulatorConfig, EBoatVessel
from ocean_warp.eboat.parts import eboat_parts
from ocean_warp.envs.protocol import episode_log
from ocean_warp.perception import Scene, SceneObject
from ocean_warp.torch_streams import ordered_with_torch
from tests.hull_setups import rotation_matrix

HULL = eboat_parts(hull_detail=1).hull.points
EBOAT = EBoatVessel()
EBOAT_SHAPE = EBOAT.collision_shape()


def still_sim(device, count, positions, headings):
    """E-Boats on still water, in calm air (no sail force), upright at rest at the given places."""
    config = EBoatSimulatorConfig(wind=ow.WindConfig(speed=0.0))
    sim = EBoatSimulator(config, count, device=device)
    sim.reset(position=positions, heading=headings)
    return sim


def test_capsule_spans_the_hull():
    stern, bow, radius = boat_capsule(HULL)
    assert radius == pytest.approx(np.abs(HULL[:, 1]).max())
    assert stern[0] - radius == pytest.approx(HULL[:, 0].min()) and bow[0] + radius == pytest.approx(HULL[:, 0].max())
    with pytest.raises(ValueError, match=r"ContactConfig\.stiffness must be >= 0"):
        ContactConfig(stiffness=-1.0)


def test_overlap_and_force_against_hand_computation(device, rng):
    """A sphere overlapping the boat's capsule side by a random depth: the boat is flagged and pushed by
    k depth along the line from the sphere's centre to the capsule's axis, at the capsule's surface."""
    stern, bow, radius = boat_capsule(HULL)
    sphere_radius = float(rng.uniform(0.3, 0.8))
    depth = float(rng.uniform(0.02, 0.1))
    along = float(rng.uniform(stern[0], bow[0]))
    center = np.array([along, radius + sphere_radius - depth, stern[2]])
    sim = still_sim(device, 1, [0.0, 0.0, 0.0], 0.0)
    scene = Scene.for_simulator(sim, objects=[SceneObject("sphere", tuple(center), radius=sphere_radius)],
                                vessel=EBOAT, water_visible=False)
    stiffness = float(rng.uniform(1e3, 1e5))
    contact = Contact(scene, ContactConfig(stiffness=stiffness, damping=0.0), shape=EBOAT_SHAPE)
    sim.fleet.forces.model_wrench.zero_()
    contact.substep(sim.simulator)
    wrench = sim.fleet.forces.model_wrench.numpy()[0]
    expected_force = np.array([0.0, -stiffness * depth, 0.0])  # pushed to starboard, away from the sphere
    np.testing.assert_allclose(wrench[:3], expected_force, rtol=1e-4, atol=1e-6 * stiffness)
    point = np.array([along, radius, stern[2]])  # where the capsule's surface meets the sphere's centre line
    np.testing.assert_allclose(wrench[3:], np.cross(point, expected_force), rtol=1e-4, atol=1e-4 * stiffness)
    assert sim.state.status.numpy()[0] & ow.BoatStatus.COLLIDED and contact.contacts.numpy()[0] == 1


def sail_with_contact(sim, contact, steps, push):
    """``steps`` steps of the simulator with ``push`` [N] forward on each boat (body frame, at its centre of
    mass); returns the boats' positions (T, N, 3) and orientations (T, N, 4) after each step."""
    sim.simulator.add_model(contact)
    with ordered_with_torch(sim.device):
        sim.tensors.control.wrench_body[:] = 0.0
        sim.tensors.control.wrench_body[:, 0] = torch.as_tensor(push, dtype=torch.float32)
    positions, orientations = [], []
    for _ in range(steps):
        sim.step()
        positions.append(sim.state.position.numpy().copy())
        orientations.append(sim.state.orientation.numpy().copy())
    return np.array(positions), np.array(orientations)


def capsule_axis(positions, orientations, stern, bow):
    """World ends (T, 2, 3) of one boat's capsule axis over a track."""
    rotations = [rotation_matrix(q) for q in orientations]
    return np.array([[p + r @ stern, p + r @ bow] for p, r in zip(positions, rotations)])


def horizontal_distance_to_segment(point_xy, ends):
    """Horizontal distance (T,) from a vertical line at ``point_xy`` to each segment of ``ends`` (T, 2, 3)."""
    a, b = ends[:, 0, :2], ends[:, 1, :2]
    ab = b - a
    t = np.clip(np.sum((point_xy - a) * ab, axis=1) / np.sum(ab * ab, axis=1), 0.0, 1.0)
    return np.linalg.norm(point_xy - (a + t[:, None] * ab), axis=1)


def test_a_boat_driven_into_a_pile_stops_outside_it(device, rng):
    """A boat pushed ahead at 60 N toward a pile 4-6 m off its bow, with contact: it is flagged, and its
    capsule never comes into the pile by more than a few centimetres (it stops against it or glances off
    it, the pile being round and frictionless); without a contact force it sails through, flagged."""
    stern, bow, radius = boat_capsule(HULL)
    pile_radius = float(rng.uniform(0.3, 0.6))
    pile_x = float(bow[0] + radius + rng.uniform(4.0, 6.0) + pile_radius)
    pile = SceneObject.pillar((pile_x, 0.0), radius=pile_radius, height=4.0)
    stopped = still_sim(device, 1, [0.0, 0.0, 0.0], 0.0)
    stopping = Contact(Scene.for_simulator(stopped, objects=[pile], vessel=EBOAT), shape=EBOAT_SHAPE)
    positions, orientations = sail_with_contact(stopped, stopping, 400, 60.0)
    clearance = horizontal_distance_to_segment(np.array([pile_x, 0.0]),
                                               capsule_axis(positions[:, 0], orientations[:, 0], stern, bow))
    touching = radius + pile_radius
    assert clearance.min() < touching + 0.01, "it reaches the pile"
    assert clearance.min() > touching - 0.06, "and does not go into it"
    assert stopped.state.status.numpy()[0] & ow.BoatStatus.COLLIDED
    free = still_sim(device, 1, [0.0, 0.0, 0.0], 0.0)
    flagging = Contact(Scene.for_simulator(free, objects=[pile], vessel=EBOAT),
                       ContactConfig(stiffness=0.0, damping=0.0),
                       shape=EBOAT_SHAPE)
    through, _ = sail_with_contact(free, flagging, 600, 60.0)
    assert through[-1, 0, 0] + stern[0] - radius > pile_x + pile_radius, "without a force it passes through"
    assert free.state.status.numpy()[0] & ow.BoatStatus.COLLIDED


def test_two_boats_meeting_head_on_are_flagged_and_kept_apart(device, rng):
    """Two boats 8-10 m apart bow to bow, each pushed ahead: both are flagged; their capsules end no closer
    than a few centimetres of touching; a third boat in another environment of the scene is not flagged."""
    stern, bow, radius = boat_capsule(HULL)
    gap = float(rng.uniform(8.0, 10.0))
    sim = still_sim(device, 3, [[0.0, 0.0, 0.0], [gap, 0.0, 0.0], [gap / 2, 30.0, 0.0]], [0.0, math.pi, 0.0])
    scene = Scene.for_vessel(EBOAT, sim, [[], []], envs=2, boat_env=[0, 0, 1])
    positions, orientations = sail_with_contact(sim, Contact(scene, shape=EBOAT_SHAPE), 400, [60.0, 60.0, 60.0])
    first = capsule_axis(positions[:, 0], orientations[:, 0], stern, bow)
    second = capsule_axis(positions[:, 1], orientations[:, 1], stern, bow)
    # Every step: the real boat, pushed to 2 m/s, may glance off the other in a few steps and sail past it.
    along = np.linspace(0.0, 1.0, 41)[None, :, None]
    points = [ends[:, :1] + along * (ends[:, 1:] - ends[:, :1]) for ends in (first, second)]  # (T, 41, 3) each
    closest = np.linalg.norm(points[0][:, :, None] - points[1][:, None, :], axis=-1).min(axis=(1, 2))
    assert closest.min() > 2 * radius - 0.08, "the capsules do not go into each other"
    assert closest.min() < 2 * radius + 0.02, "they met"
    status = sim.state.status.numpy()
    assert status[0] & ow.BoatStatus.COLLIDED and status[1] & ow.BoatStatus.COLLIDED
    assert not status[2] & ow.BoatStatus.COLLIDED


def test_the_episode_log_counts_collisions():
    done = torch.tensor([True, True, False])
    status = torch.tensor([ow.BoatStatus.COLLIDED, 0, ow.BoatStatus.COLLIDED], dtype=torch.int32)

    class Buffers:
        pass

    b = Buffers()
    b.done, b.final_status, b.time_out = done, status, torch.zeros(3, dtype=torch.bool)
    b.final_return, b.final_length = torch.zeros(3), torch.ones(3, dtype=torch.int32)
    b.final_success, b.final_waypoints = torch.zeros(3), torch.zeros(3, dtype=torch.int32)
    log = episode_log(b)
    assert log["/episode/collided_rate"].tolist() == [1.0, 0.0]



def test_a_boat_driven_into_a_mesh_object_stops_at_its_face(device, rng, tmp_path):
    """A box read from an STL file (a quay), 3-5 m off the bow: the capsule's front stops within a few
    centimetres of the box's near face (the mesh's nearest points, sampled along the capsule's axis)."""
    import trimesh

    stern, bow, radius = boat_capsule(HULL)
    trimesh.creation.box(extents=(2.0, 6.0, 3.0)).export(tmp_path / "quay.stl")
    face_x = float(bow[0] + radius + rng.uniform(3.0, 5.0))
    quay = SceneObject.from_file(tmp_path / "quay.stl", (face_x + 1.0, 0.0, 0.5))
    sim = still_sim(device, 1, [0.0, 0.0, 0.0], 0.0)
    contact = Contact(Scene.for_simulator(sim, objects=[quay], vessel=EBOAT), shape=EBOAT_SHAPE)
    positions, orientations = sail_with_contact(sim, contact, 300, 60.0)
    front = capsule_axis(positions[:, 0], orientations[:, 0], stern, bow)[:, 1, 0] + radius
    assert front.max() > face_x - 0.01, "it reaches the quay"
    assert front.max() < face_x + 0.06, "and does not go into it"
    assert sim.state.status.numpy()[0] & ow.BoatStatus.COLLIDED


def test_each_vessel_collides_as_its_own_capsule(device, rng):
    """A sphere abeam, between the E-Boat's reach and the WAM-V's: the WAM-V (its capsule holds both pontoons:
    half the spacing plus a pontoon's 16-gon section radius, VRX's figures) touches it, the E-Boat does not.
    A caller that passes no vessel shape is told so."""
    from ocean_warp.contact import contact_model
    from ocean_warp.wamv import Wamv

    sphere_radius = 0.3
    polygon = math.sqrt(2.0 * math.pi / (16 * math.sin(2.0 * math.pi / 16)))  # equal-area 16-gon / circle
    wamv_reach = 0.5 * 2.06 + 0.213 * polygon + sphere_radius  # pontoon spacing 2.06 m, radius 0.213 m
    eboat_reach = float(np.abs(HULL[:, 1]).max()) + sphere_radius  # half beam
    assert eboat_reach + 0.2 < wamv_reach - 0.2
    abeam = float(rng.uniform(eboat_reach + 0.1, wamv_reach - 0.1))
    sphere = SceneObject("sphere", (-0.4, abeam, 0.0), radius=sphere_radius)  # beside the pontoons' middle
    flagged = {}
    for name, vessel in (("wamv", Wamv()), ("eboat", EBoatVessel())):
        sim = vessel.simulator(1, device=device)
        sim.reset(position=[0.0, 0.0, 0.0], heading=0.0)
        scene = Scene.for_vessel(vessel, sim, [[sphere]], envs=1, boat_env=[0], water_visible=False)
        contact = Contact(scene, ContactConfig(stiffness=0.0, damping=0.0), shape=vessel.collision_shape())
        contact.substep(sim.simulator)
        flagged[name] = bool(sim.state.status.numpy()[0] & ow.BoatStatus.COLLIDED)
        assert contact.contacts.numpy()[0] == int(flagged[name])
    assert flagged == {"wamv": True, "eboat": False}
    with pytest.raises(ValueError, match="contact_model: shape must be the vessel's CollisionShape"):
        contact_model(ContactConfig(), None)
