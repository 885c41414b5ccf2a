"""``ocean-warp demo`` and ``ocean-warp export-usd`` end to end on tiny settings (CPU)."""

from __future__ import annotations

import csv
import dataclasses

import numpy as np
import pytest

pytest.importorskip("pxr", reason="USD tests need usd-core (pip install usd-core)")
from pxr import Usd, UsdGeom  # noqa: E402

from ocean_warp import cli
from ocean_warp.envs.apps.demo import DemoConfig, run_demo
from ocean_warp.envs.apps.usd_export import ExportConfig, export_scenario
from ocean_warp.usd import validate_stage
from ocean_warp.usd.paths import FLEET


def _rows(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def test_tiny_demo_writes_stage_pictures_and_table(tmp_path):
    config = DemoConfig(boats=5, policy_share=0.6, time_limit=6.0, frames_per_second=2, ocean_resolution=8,
                        loop_period=4.0)
    result = run_demo(config, device="cpu", out=tmp_path, progress=False)
    for name in ("stage", "ocean loop", "preview", "results.csv", "runs.csv", "trajectories.png"):
        assert name in result.files and (tmp_path / result.files[name].split("/")[-1]).stat().st_size > 0, name
    table = _rows(result.files["results.csv"])
    assert [(row["controller"], row["runs"]) for row in table] == [("policy", "3"), ("autopilot", "2")]
    runs = _rows(result.files["runs.csv"])
    assert [row["controller"] for row in runs] == ["policy"] * 3 + ["autopilot"] * 2
    assert all(row["end"] == "time-out" for row in runs)  # 6 s is far too short for the mission
    # the autopilot's own tack and gybe counts fill its rows (the policy keeps none: empty)
    for key in ("own_tacks", "own_gybes"):
        assert [row[key] for row in runs[:3]] == [""] * 3 and all(row[key].isdigit() for row in runs[3:]), key
    # 5 boats x 6 decisions of 1 s each
    assert result.simulated_boat_seconds == pytest.approx(30.0)
    stage = Usd.Stage.Open(result.files["stage"])
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.z
    # 2 frames a simulated second, at 24 time codes a second (so the stage plays in real time in Blender)
    assert stage.GetTimeCodesPerSecond() == stage.GetFramesPerSecond() == 24.0
    assert (stage.GetStartTimeCode(), stage.GetEndTimeCode()) == (12.0, 144.0)  # frames at 0.5 s ... 6 s
    # The mission BCDACA starts at A: the drawn route does too.
    route = np.array(UsdGeom.BasisCurves.Get(stage, "/World/Route/Path").GetPointsAttr().Get())[:, :2]
    np.testing.assert_allclose(route - route[0], np.array([[0.0, 0.0], [70.71, -70.71], [141.42, 0.0],
                                                           [70.71, 70.71], [0.0, 0.0], [141.42, 0.0], [0.0, 0.0]]),
                               atol=1e-3)
    assert stage.GetPrimAtPath(FLEET).GetAttribute("oceanWarp:boatCount").Get() == 5
    assert validate_stage(result.files["stage"]) == []
    # Each boat sailed by the controller its row names: a fleet of one controller, on the same water with
    # the same starts and gusts, sails those boats the same way (boats 0-2 the policy, 3-4 the autopilot).
    for share, boats, name in ((1.0, slice(0, 3), "policy"), (0.0, slice(3, 5), "autopilot")):
        alone = run_demo(dataclasses.replace(config, policy_share=share, usd=False), device="cpu",
                         out=tmp_path / name, progress=False)
        reference = _rows(alone.files["runs.csv"])[boats]
        mixed = [row for row in runs if row["controller"] == name]
        for key in ("distance_m", "motor_use", "start_heading_deg", "own_tacks", "own_gybes"):
            assert [row[key] for row in mixed] == [row[key] for row in reference], key
    policy_distance = [float(row["distance_m"]) for row in runs[:3]]
    assert policy_distance != [float(row["distance_m"]) for row in _rows(alone.files["runs.csv"])[:3]]


def test_export_usd_fixed_commands_move_the_boats_as_commanded(tmp_path):
    """Full throttle straight ahead (motor level 5, rudder 0) for 8 s: every boat moves several metres and
    its recorded rudder stays near zero; the stage is per-prim below the instancing threshold."""
    config = ExportConfig(boats=3, duration=8.0, controller="fixed", actions=(1.0, -1.0, 0.0), frames_per_second=1,
                          ocean_resolution=8, hull="points")
    files = export_scenario(config, tmp_path / "fixed.usda", device="cpu", progress=False)
    stage = Usd.Stage.Open(files["stage"])
    boats = [prim for prim in stage.GetPrimAtPath(FLEET).GetChildren() if prim.GetName().startswith("Boat_")]
    assert len(boats) == 3
    # Frames at 1 s ... 8 s, at 24 time codes per second.
    assert (stage.GetStartTimeCode(), stage.GetEndTimeCode(), stage.GetTimeCodesPerSecond()) == (24.0, 192.0, 24.0)
    for prim in boats:
        xform = UsdGeom.Xformable(prim)
        start = np.array(xform.ComputeLocalToWorldTransform(24.0).ExtractTranslation())
        end = np.array(xform.ComputeLocalToWorldTransform(192.0).ExtractTranslation())
        assert np.linalg.norm(end[:2] - start[:2]) > 3.0


def test_cli_help_and_bad_options(capsys, tmp_path):
    for job in ("demo", "export-usd"):
        with pytest.raises(SystemExit) as exit_info:
            cli.main([job, "--help"])
        assert exit_info.value.code == 0
        assert "[m/s]" in capsys.readouterr().out
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["demo", "--boats", "0", "--no-usd"])
    assert exit_info.value.code == 2
    error = capsys.readouterr().err.strip()
    assert error.startswith("ocean-warp demo:") and "boats" in error and "\n" not in error
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["export-usd", "--controller", "fixed", "--actions", "2,0,0"])
    assert exit_info.value.code == 2
    assert "actions" in capsys.readouterr().err
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    for argv, name in ((["demo", "--fps", "3", "--no-usd"], "frames_per_second"),
                       (["demo", "--no-usd", "--out", str(blocker / "demo")], "a_file"),
                       (["export-usd", "--out", str(blocker / "x.usdc")], "a_file"),
                       (["export-usd", "--duration", "0.3"], "duration")):
        with pytest.raises(SystemExit) as exit_info:
            cli.main(argv)
        assert exit_info.value.code == 2, argv
        error = capsys.readouterr().err.strip().splitlines()
        assert len(error) == 1 and name in error[0], (argv, error)


def test_ctrl_c_ends_a_command_with_one_line_and_code_130(monkeypatch, capsys):
    """Ctrl-C (KeyboardInterrupt) inside any job: exit status 130 and one line on stderr, no traceback."""
    import ocean_warp.envs.apps.demo as demo

    def interrupted(argv):
        raise KeyboardInterrupt

    monkeypatch.setattr(demo, "main", interrupted)
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["demo", "--boats", "2"])
    assert exit_info.value.code == 130
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["ocean-warp demo: interrupted; files written before it are complete"]


# --- --task: any registered task, obstacles in the stage --------------------------------------------

def test_export_usd_of_an_avoid_task(tmp_path, capsys):
    """``export-usd --task ocean_warp/EBoatAvoid-v0``: the task's shipped policy steers, or, where it has none,
    the autopilot (said in one line); the stage holds every boat's obstacles (one prim each) and validates."""
    from ocean_warp.envs.training import policies
    from ocean_warp.usd.paths import OBJECTS

    out = tmp_path / "avoid.usda"
    cli.main(["export-usd", "--task", "ocean_warp/EBoatAvoid-v0", "--boats", "2", "--duration", "2", "--fps", "1",
              "--ocean-resolution", "8", "--hull", "points", "--out", str(out), "--no-progress"])
    printed = capsys.readouterr().out
    assert ("no policy is shipped for EBoatAvoid-v0" in printed) == ("EBoatAvoid-v0" not in policies.SHIPPED_POLICIES)
    assert "of EBoatAvoid-v0" in printed
    stage = Usd.Stage.Open(str(out))
    objects = stage.GetPrimAtPath(OBJECTS).GetChildren()
    assert len(objects) >= 2 * 6  # 6-12 obstacles for each boat
    assert {p.GetDisplayName().split()[2] for p in objects} == {"buoy", "pile"}
    assert validate_stage(out) == []


def test_tiny_demo_of_an_avoid_task(tmp_path):
    """The demo on EBoatAvoid-v0: its shipped policy's share of the boats, or every boat the autopilot's where
    it has none; the table has the collisions column, the stage each boat's obstacles."""
    from ocean_warp.envs.training import policies
    from ocean_warp.usd.paths import OBJECTS

    config = DemoConfig(boats=2, time_limit=3.0, frames_per_second=1, ocean_resolution=8, loop_period=4.0,
                        hull="points", task_id="EBoatAvoid-v0")
    result = run_demo(config, device="cpu", out=tmp_path, progress=False)
    shipped = "EBoatAvoid-v0" in policies.SHIPPED_POLICIES
    table = _rows(result.files["results.csv"])
    assert [row["controller"] for row in table] == (["policy", "autopilot"] if shipped else ["autopilot"])
    assert all(row["collisions"].isdigit() for row in table)
    stage = Usd.Stage.Open(result.files["stage"])
    assert len(stage.GetPrimAtPath(OBJECTS).GetChildren()) >= 2 * 6
    assert validate_stage(result.files["stage"]) == []
    for controller in result.evaluation.results.values():
        assert controller.has_obstacles


@pytest.mark.parametrize("job", ["demo", "export-usd"])
def test_an_unknown_task_is_a_one_line_error(job, tmp_path, capsys):
    out = tmp_path / ("demo" if job == "demo" else "x.usdc")
    with pytest.raises(SystemExit) as exit_info:
        cli.main([job, "--task", "EBoatNowhere-v0", "--out", str(out)])
    assert exit_info.value.code == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and "--task: unknown task id 'EBoatNowhere-v0'; known: EBoatWaypoint-v0" in error[0], error
    assert not out.exists()


# --- demo --policy: a trained checkpoint sails the policy's share ------------------------------------

def test_demo_sails_the_given_policy(tmp_path, capsys):
    """--policy FILE: the policy's share of the boats sails that checkpoint. Its output layer always commands
    propeller int(5 x 0) = 0, so its boats never use the motor, while the autopilot's boat is the autopilot's."""
    from tests.envs.apps.test_evaluation import random_policy_file

    policy = tmp_path / "policy.pt"
    random_policy_file(policy, constant_actions=(0.0, 0.2, 0.1))
    out = tmp_path / "demo"
    cli.main(["demo", "--policy", str(policy), "--boats", "3", "--policy-share", "0.67", "--time-limit", "3",
              "--no-usd", "--no-progress", "--device", "cpu", "--out", str(out)])
    printed = capsys.readouterr().out.splitlines()
    assert printed[:2] == ["EBoatMission-v0: 3 boats, device cpu",
                           f"policy {policy}: for EBoatMission-v0, observation 'seed' (6 values)"], printed
    runs = _rows(out / "runs.csv")
    assert [row["controller"] for row in runs] == ["policy", "policy", "autopilot"]
    assert [float(row["motor_use"]) for row in runs[:2]] == [0.0, 0.0]
    assert all(row["own_tacks"] == "" for row in runs[:2]) and runs[2]["own_tacks"].isdigit()


def test_demo_refuses_an_unusable_policy_before_sailing(tmp_path, capsys):
    """Any file that is not a policy checkpoint: one line naming it, exit status 2, nothing written."""
    from tests.envs.apps.test_evaluation import unusable_checkpoints

    out = tmp_path / "demo"
    for name, message in unusable_checkpoints(tmp_path).items():
        with pytest.raises(SystemExit) as exit_info:
            cli.main(["demo", "--policy", str(tmp_path / name), "--device", "cpu", "--out", str(out)])
        assert exit_info.value.code == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith(f"ocean-warp demo: error: --policy: checkpoint "
                                                   f"{str(tmp_path / name)!r}") and message in err[0], (name, err)
    assert not out.exists()
