"""A stage of any vessel: a VrxEnv of WAM-Vs recorded decision by decision holds each boat's parts (one prim per
part of ``Vessel.parts()``), and USD's world transform of each part's mesh puts it where the env's buffers
(poses) and the simulator's thruster angles do, worked out with scipy's rotations."""

from __future__ import annotations

import numpy as np
import pytest
import torch
from scipy.spatial.transform import Rotation

pytest.importorskip("pxr", reason="USD tests need usd-core (pip install usd-core)")
from pxr import Usd, UsdGeom  # noqa: E402

from ocean_warp.envs.vrx import VrxEnv, VrxTaskConfig  # noqa: E402
from ocean_warp.usd import FleetDrawing, StageRecorder, record_vessel, validate_stage  # noqa: E402
from ocean_warp.wamv import Wamv, WamvConfig, WamvSimulatorConfig  # noqa: E402
from ocean_warp.wamv.config import ThrusterLayout  # noqa: E402

PARTS = ("pontoons", "frame", "left_thruster", "right_thruster")
"""The WAM-V's parts as the stage names them."""


@pytest.mark.parametrize("instanced", [False, True], ids=["prim_per_boat", "instanced"])
def test_a_stage_of_two_wamvs_follows_the_simulated_poses(tmp_path, rng, instanced):
    vessel = Wamv(WamvSimulatorConfig(boat=WamvConfig(thrusters=ThrusterLayout.AZIMUTH)))
    env = VrxEnv(VrxTaskConfig(kind="wayfinding", goals=2, vessel=vessel), 2, device="cpu",
                 seed=int(rng.integers(1 << 30)))
    path = tmp_path / "wamv.usda"
    frames = []
    with StageRecorder.for_vessel(path, vessel, env.simulator, fps=2.0, ocean=None, wind=None,
                                  fleet=FleetDrawing(2, vessel=vessel, instanced=instanced)) as recorder:
        for _ in range(3):
            env.step(torch.as_tensor(rng.uniform(-1, 1, (2, env.num_actions)), dtype=torch.float32,
                                     device=env.torch_device))
            record_vessel(recorder, env.simulator)
            frames.append(dict(code=recorder.last_time_code,
                               position=env.buffers.position.cpu().numpy().astype(np.float64),
                               orientation=env.buffers.orientation.cpu().numpy().astype(np.float64),
                               angle=env.simulator.state.thruster_angle.numpy().astype(np.float64)))
    assert validate_stage(str(path)) == []
    assert np.any(np.abs(frames[-1]["angle"]) > 1e-3)  # the thrusters turned: the joints are exercised
    stage = Usd.Stage.Open(str(path))
    parts = {part.name: part for part in vessel.parts()}
    for name in PARTS:
        local = np.array(UsdGeom.Mesh.Get(stage, f"/Library/WAM_V/{name}/Mesh").GetPointsAttr().Get(), np.float64)
        np.testing.assert_allclose(local, parts[name].mesh.points, atol=1e-6)
    for frame in frames:
        code = frame["code"]
        cache = UsdGeom.XformCache(code)
        if instanced:
            instancers = {name: UsdGeom.PointInstancer(stage.GetPrimAtPath(f"/World/Fleet/{name}")) for name in PARTS}
            matrices = {name: [np.array(m) for m in instancer.ComputeInstanceTransformsAtTime(code, code)]
                        for name, instancer in instancers.items()}
        else:
            matrices = {name: [np.array(cache.GetLocalToWorldTransform(stage.GetPrimAtPath(
                f"/World/Fleet/Boat_{boat:04d}/{name}"))) for boat in range(2)] for name in PARTS}
        for boat in range(2):
            if not instanced:
                assert sorted(child.GetName() for child in stage.GetPrimAtPath(f"/World/Fleet/Boat_{boat:04d}")
                              .GetChildren()) == sorted(PARTS)
            pose = Rotation.from_quat(frame["orientation"][boat])
            for name in PARTS:
                part = parts[name]
                points = part.mesh.points
                if part.joint is not None:
                    turn = Rotation.from_euler("z", -frame["angle"][boat, part.joint_column])
                    points = turn.apply(points) + part.pivot
                expected = pose.apply(points) + frame["position"][boat]
                drawn = np.c_[part.mesh.points, np.ones(len(points))] @ matrices[name][boat]
                np.testing.assert_allclose(drawn[:, :3], expected, atol=1e-4, err_msg=f"boat {boat} {name}")


def test_a_vessel_fleet_refuses_missing_joints_and_levels_it_has_none_of(tmp_path):
    vessel = Wamv()
    with pytest.raises(ValueError, match=r"FleetDrawing\.vessel: expected a vessel"):
        FleetDrawing(2, vessel="WAM-V")
    recorder = StageRecorder(tmp_path / "bad.usda", fps=2.0, fleet=FleetDrawing(2, vessel=vessel))
    try:
        where, facing = np.zeros((2, 3)), [[0.0, 0.0, 0.0, 1.0]] * 2
        with pytest.raises(ValueError, match=r"joints\['thruster_angle'\] is required"):
            recorder.record(0.0, where, facing)
        with pytest.raises(ValueError, match=r"levels given, but the WAM-V draws no part at a size of each boat's"):
            recorder.record(0.0, where, facing, joints={"thruster_angle": np.zeros((2, 2))}, levels=[0, 0])
        with pytest.raises(ValueError, match=r"joints\['thruster_angle'\] must have shape \(2,\) or \(2, C\)"):
            recorder.record(0.0, where, facing, joints={"thruster_angle": np.zeros((3, 2))})
    finally:
        recorder.abort()


def test_export_usd_records_a_vrx_task_part_by_part(tmp_path):
    """``ocean-warp export-usd --task WamvStationKeeping-v0``: every WAM-V with its parts as prims, one frame a
    decision (a 4 s run of 0.5 s decisions: 9 time codes), a valid stage."""
    from ocean_warp.envs.apps.usd_export import main

    path = tmp_path / "wamv.usdc"
    assert main(["--task", "WamvStationKeeping-v0", "--boats", "2", "--duration", "4", "--out", str(path),
                 "--device", "cpu", "--no-progress"]) == 0
    stage = Usd.Stage.Open(str(path))
    parts = sorted(part.name for part in Wamv().parts())
    for boat in range(2):
        prim = stage.GetPrimAtPath(f"/World/Fleet/Boat_{boat:04d}")
        assert prim.IsValid() and sorted(child.GetName() for child in prim.GetChildren()) == parts
    times = UsdGeom.Xformable(stage.GetPrimAtPath("/World/Fleet/Boat_0000")).GetTimeSamples()
    assert len(times) == 9
    assert not validate_stage(str(path))
