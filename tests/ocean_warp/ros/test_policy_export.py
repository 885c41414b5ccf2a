"""Policies for the boat (ocean_warp.envs.ros.policy_export, onnx_policy): ONNX run by onnxruntime and TorchScript run
by torch.jit.load reproduce every shipped policy's actions to 1e-5, normalisation inside the graph; the metadata
comes back; ``ocean-warp export-policy`` writes the file or fails in one line; the runner needs neither torch
nor Warp."""

from __future__ import annotations

import importlib.util
import subprocess
import sys

import numpy as np
import pytest
import torch

from ocean_warp import cli
from ocean_warp.envs.ros import policy_export
from ocean_warp.envs.ros.policy_export import (ActionDifference, ExportError, export_onnx, export_torchscript,
                                               policy_metadata, read_torchscript_metadata)
from ocean_warp.envs.registration import make_task_config
from ocean_warp.envs.tasks.observation_blocks import policy_layout
from ocean_warp.envs.tasks.task_kernels import POLICY_OBS
from ocean_warp.envs.training.policies import SHIPPED_POLICIES, shipped_policy_path
from ocean_warp.envs.training.policy_io import CHECKPOINT_FORMAT, load_policy
from ocean_warp.ros import onnx_policy
from ocean_warp.ros.onnx_policy import EXPORT_FORMAT, OnnxPolicy

pytestmark = pytest.mark.filterwarnings("ignore:`torch.jit.load` is deprecated:DeprecationWarning")
HAS_ONNX = all(importlib.util.find_spec(name) is not None for name in ("onnx", "onnxruntime"))
needs_onnx = pytest.mark.skipif(not HAS_ONNX, reason="needs the onnx extra (onnx, onnxruntime): "
                                                     "pip install 'ocean-warp[onnx]'")
TASKS = sorted(SHIPPED_POLICIES)
TOLERANCE = 1e-5
ERROR = "ocean-warp export-policy: error: "


def realistic_observations(policy, count: int, seed: int) -> np.ndarray:
    """(count, num_obs) float32: a quarter drawn as in training (the normaliser's mean + std N(0, 1)), a
    quarter 3-5 standard deviations out (far from the mean), a quarter uniform in [-1, 1] (the seed set's
    range), a quarter the far ones clipped to [-1, 1]."""
    rng = np.random.default_rng(seed)
    mean = policy.actor.obs_normalizer.mean.numpy()
    std = policy.actor.obs_normalizer.std.numpy()
    quarter = count // 4
    typical = mean + std * rng.standard_normal((quarter, policy.num_obs))
    far = mean + std * rng.choice([-1.0, 1.0], (quarter, policy.num_obs)) * rng.uniform(3.0, 5.0, (quarter, 1))
    uniform = rng.uniform(-1.0, 1.0, (count - 3 * quarter, policy.num_obs))
    rows = np.concatenate([typical, far, uniform, np.clip(far, -1.0, 1.0)])
    return rows[rng.permutation(count)].astype(np.float32)


def torch_actions(policy, observations: np.ndarray) -> np.ndarray:
    return policy(torch.from_numpy(observations)).numpy()


@pytest.fixture(scope="module")
def exports(tmp_path_factory):
    """task id -> (policy, path of its ONNX export or None without the extra, path of its TorchScript export),
    each exported once for the module."""
    folder = tmp_path_factory.mktemp("exports")
    made = {}
    for task in TASKS:
        source = shipped_policy_path(task)
        onnx_path = folder / f"{source.stem}.onnx" if HAS_ONNX else None
        if HAS_ONNX:
            export_onnx(source, onnx_path)
        export_torchscript(source, folder / f"{source.stem}.pt")
        made[task] = (load_policy(source), onnx_path, folder / f"{source.stem}.pt")
    return made


def assert_reproduces(policy, act, batch_size: int, seed: int) -> ActionDifference:
    """``act`` (numpy batch -> actions) against the torch policy on realistic observations, both in batches
    of ``batch_size`` (torch's own float32 sums differ by some 1e-6 between batch sizes): the clipped actions
    to 1e-5, the unclipped means to 1e-5 (absolute up to 1, relative beyond), and the means within [-1, 1]
    to 1e-5 absolute."""
    observations = realistic_observations(policy, 64, seed)
    batches = [observations[k:k + batch_size] for k in range(0, len(observations), batch_size)]
    expected = np.concatenate([torch_actions(policy, batch) for batch in batches])
    actual = np.concatenate([act(batch) for batch in batches])
    assert actual.shape == expected.shape and actual.dtype == np.float32
    difference = ActionDifference.between(expected, actual)
    assert difference.within(TOLERANCE), difference.text()
    inside = np.abs(expected) <= 1.0
    assert inside.any() and np.abs(actual - expected)[inside].max() <= TOLERANCE
    assert np.abs(expected).max() > 0.1  # the observations are not all alike: the policy acts on them
    print(f"{policy.task} batch {batch_size}: {difference.text()}")
    return difference


@needs_onnx
@pytest.mark.parametrize("batch_size", [1, 64])
@pytest.mark.parametrize("task", TASKS)
def test_onnxruntime_reproduces_every_shipped_policy(task, batch_size, exports):
    policy, onnx_path, _ = exports[task]
    runner = OnnxPolicy(onnx_path)
    if batch_size == 1:  # one observation of shape (num_obs,) at a time, as the node acts
        assert_reproduces(policy, lambda rows: runner.act(rows[0])[None], 1, seed=11)
    else:
        assert_reproduces(policy, runner.act, batch_size, seed=12)


@pytest.mark.parametrize("batch_size", [1, 64])
@pytest.mark.parametrize("task", TASKS)
def test_torchscript_reproduces_every_shipped_policy(task, batch_size, exports):
    policy, _, script_path = exports[task]
    module = torch.jit.load(str(script_path))
    assert_reproduces(policy, lambda rows: module(torch.from_numpy(rows)).numpy(), batch_size, seed=13)


def perturbed(policy):
    """``policy`` with its normaliser's statistics moved (mean + 0.5 std, std x 1.7): the same weights."""
    normaliser = policy.actor.obs_normalizer
    with torch.no_grad():
        normaliser._mean += 0.5 * normaliser._std
        normaliser._std *= 1.7
    return policy


@pytest.mark.parametrize("form", [pytest.param("onnx", marks=needs_onnx), "torchscript"])
def test_the_normalisation_is_inside_the_graph(form, exports, tmp_path):
    """A policy whose normaliser statistics alone are changed acts differently, and its export follows it,
    not the original: the statistics are in the file, and the file takes raw observations."""
    original, onnx_path, script_path = exports["EBoatWaypoint-v0"]
    changed = perturbed(load_policy(shipped_policy_path("EBoatWaypoint-v0")))
    observations = realistic_observations(original, 64, seed=21)
    before, after = torch_actions(original, observations), torch_actions(changed, observations)
    assert np.abs(np.clip(after, -1, 1) - np.clip(before, -1, 1)).max() > 0.05
    if form == "onnx":
        export_onnx(changed, tmp_path / "changed.onnx")
        run_original, run_changed = OnnxPolicy(onnx_path).act, OnnxPolicy(tmp_path / "changed.onnx").act
    else:
        export_torchscript(changed, tmp_path / "changed.pt")
        modules = [torch.jit.load(str(path)) for path in (script_path, tmp_path / "changed.pt")]
        run_original, run_changed = (lambda rows, m=m: m(torch.from_numpy(rows)).numpy() for m in modules)
    assert ActionDifference.between(after, run_changed(observations)).within(TOLERANCE)
    assert ActionDifference.between(before, run_original(observations)).within(TOLERANCE)
    assert not ActionDifference.between(before, run_changed(observations)).within(0.05)


def test_the_layouts_are_the_task_layers_blocks():
    """Each value's line is its declared column's (``observation_blocks``), one per value the kernels fill;
    a policy of an unknown set or task gets placeholders of the right count."""
    for task in TASKS:
        config = make_task_config(task)
        if hasattr(config, "vessel"):  # VRX's tasks: their own block and the vessel's actions (tests/envs/vrx)
            continue
        expected = [column.text() for column in policy_layout(config)]
        assert policy_export.observation_layout(task, config.observation.value, len(expected)) == expected
    layout = policy_export.observation_layout("EBoatWaypoint-v0", "seed", POLICY_OBS["seed"] + 2)
    assert layout[-2:] == ["value 5 (appended by EBoatWaypoint-v0: not described here)",
                           "value 6 (appended by EBoatWaypoint-v0: not described here)"]
    assert len(policy_export.observation_layout("EBoatWaypoint-v0", "other", 4)) == 4


@pytest.mark.parametrize("task", TASKS)
def test_metadata_round_trip(task, exports):
    policy, onnx_path, script_path = exports[task]
    source = shipped_policy_path(task)
    actions = 2 if task.startswith("Wamv") else 3  # the WAM-V's two thrusters, the E-Boat's propeller, sheet, rudder
    stored = policy_metadata(policy, source)
    read = [read_torchscript_metadata(script_path)] + ([OnnxPolicy(onnx_path).metadata] if HAS_ONNX else [])
    for metadata in read:
        assert metadata == onnx_policy.decode_metadata(stored)
        assert metadata["format"] == EXPORT_FORMAT and metadata["checkpoint_format"] == CHECKPOINT_FORMAT
        assert (metadata["task"], metadata["observation"], metadata["num_obs"], metadata["num_actions"]) == (
            task, policy.observation, policy.num_obs, actions)
        assert len(metadata["observation_layout"]) == policy.num_obs and len(metadata["actions"]) == actions
        assert metadata["source"] == source.name and len(metadata["source_sha256"]) == 64
        assert ("ignored" in metadata["actions"][0]) == task.endswith("Sail-v0")
        assert metadata["observation_normalisation"].startswith("inside")
    if task == "EBoatAvoid-v0":
        layout = read[0]["observation_layout"]
        assert layout[5].startswith("reef_level: reef level")
        assert layout[6].startswith("lidar_sector_0: ") and "/ 50 m" in layout[6] and "sector_23" in layout[-1]
    if HAS_ONNX:
        runner = OnnxPolicy(onnx_path)
        assert (runner.task, runner.observation, runner.num_obs, runner.num_actions) == (
            task, policy.observation, policy.num_obs, actions)
        assert runner.observation_layout == read[0]["observation_layout"]
        assert runner.action_meaning[-1].startswith("a2 rudder angle: 60 deg" if actions == 3 else "a1 right_thrust")


def test_a_policy_object_has_no_source(tmp_path):
    policy = load_policy(shipped_policy_path("EBoatWaypoint-v0"))
    summary = export_torchscript(policy, tmp_path / "p.pt")
    assert "source" not in summary.metadata and "source" not in read_torchscript_metadata(tmp_path / "p.pt")
    assert summary.difference.absolute == 0.0
    with pytest.raises(ValueError, match="is not an exported TorchScript policy"):
        read_torchscript_metadata(shipped_policy_path("EBoatWaypoint-v0"))


@needs_onnx
def test_the_torchscript_based_onnx_exporter_gives_the_same(tmp_path, monkeypatch):
    """Where onnxscript is missing the export falls back to torch's TorchScript-based ONNX exporter."""
    monkeypatch.setattr(policy_export, "_uses_dynamo_exporter", lambda: False)
    policy = load_policy(shipped_policy_path("EBoatMissionSail-v0"))
    export_onnx(policy, tmp_path / "legacy.onnx")
    assert_reproduces(policy, OnnxPolicy(tmp_path / "legacy.onnx").act, 64, seed=31)


def run_job(argv, capsys):
    """``ocean-warp export-policy argv``: (exit status, stdout lines, stderr lines)."""
    try:
        cli.main(["export-policy", *map(str, argv)])
        code = 0
    except SystemExit as stop:
        code = stop.code
    captured = capsys.readouterr()
    return code, captured.out.strip().splitlines(), captured.err.strip().splitlines()


@needs_onnx
def test_the_job_writes_an_onnx_file(tmp_path, capsys):
    out = tmp_path / "boat" / "waypoint.onnx"
    code, printed, errors = run_job(["--task", "EBoatWaypoint-v0", "--out", out], capsys)
    assert code == 0 and errors == [] and len(printed) == 1, (printed, errors)
    assert printed[0].startswith(f"wrote {out}: ONNX opset {policy_export.OPSET}, the EBoatWaypoint-v0 policy")
    assert "onnxruntime reproduces the torch policy" in printed[0]
    assert OnnxPolicy(out).task == "EBoatWaypoint-v0"
    assert sorted(path.name for path in out.parent.iterdir()) == ["waypoint.onnx"]  # no temporary left


def test_the_job_writes_torchscript_by_default_path(tmp_path, capsys, monkeypatch):
    """Without --out: out/export-policy/<checkpoint>.torchscript.pt; --policy with the matching --task."""
    monkeypatch.chdir(tmp_path)
    source = shipped_policy_path("EBoatMission-v0")
    code, printed, errors = run_job(["--policy", source, "--task", "EBoatMission-v0", "--format", "torchscript"],
                                    capsys)
    written = tmp_path / "out" / "export-policy" / "eboat_mission.torchscript.pt"
    assert code == 0 and errors == [] and len(printed) == 1 and written.is_file(), (printed, errors)
    assert read_torchscript_metadata(written)["task"] == "EBoatMission-v0"


def test_the_format_follows_the_suffix(tmp_path, capsys):
    code, printed, _ = run_job(["--out", tmp_path / "mission.pt"], capsys)
    assert code == 0 and "TorchScript, the EBoatMission-v0 policy" in printed[0]


@pytest.fixture
def not_policies(tmp_path, exports):
    """A text file, an exported TorchScript archive (a torch zip, not a checkpoint) and a folder."""
    text = tmp_path / "notes.pt"
    text.write_text("not a policy")
    (tmp_path / "folder.pt").mkdir()
    return {"text": text, "torchscript": exports["EBoatWaypoint-v0"][2], "folder": tmp_path / "folder.pt"}


BAD_INPUTS = [
    (["--policy", "{tmp}/missing.pt"], "missing.pt': no such file"),
    (["--policy", "{text}"], "is not an ocean_warp policy checkpoint"),
    (["--policy", "{torchscript}"], ".pt: a TorchScript archive (an exported policy?), not a policy checkpoint"),
    (["--format", "tflite"], "--format must be onnx or torchscript, got tflite"),
    (["--format", "onnx", "--out", "{tmp}/p.pt"], "--out must end in .onnx for --format onnx, got "),
    (["--format", "torchscript", "--out", "{tmp}/p.onnx"], "--out must end in .pt for --format torchscript"),
    (["--out", "{tmp}/p.txt"], "--out must end in .onnx (ONNX) or .pt (TorchScript), got "),
    (["--out", "{folder}"], "folder.pt: is a folder, not a file"),
    (["--task", "EBoatNowhere-v0"], "--task: no policy is shipped for task 'EBoatNowhere-v0'"),
    (["--policy", str(shipped_policy_path("EBoatWaypoint-v0")), "--task", "EBoatMission-v0"],
     "holds a policy for EBoatWaypoint-v0, not EBoatMission-v0"),
]


@pytest.mark.parametrize("argv, message", BAD_INPUTS)
def test_bad_inputs_are_one_line_errors(argv, message, tmp_path, not_policies, capsys):
    names = {"tmp": tmp_path, **not_policies}
    argv = [item.format(**names) for item in argv]
    before = sorted(tmp_path.iterdir())
    code, printed, errors = run_job(argv + ([] if "--out" in argv else ["--out", tmp_path / "p.pt"]), capsys)
    assert code == 2 and printed == [] and len(errors) == 1, errors
    assert errors[0].startswith(ERROR) and message in errors[0], errors
    assert sorted(tmp_path.iterdir()) == before


def test_a_missing_onnx_package_is_a_one_line_error(tmp_path, capsys, monkeypatch):
    real = importlib.util.find_spec
    monkeypatch.setattr(policy_export.importlib.util, "find_spec",
                        lambda name, *rest: None if name == "onnx" else real(name, *rest))
    code, _, errors = run_job(["--out", tmp_path / "p.onnx"], capsys)
    assert code == 2 and errors == [f"{ERROR}--format onnx needs the onnx package: pip install 'ocean-warp[onnx]'"]
    assert not (tmp_path / "p.onnx").exists()


@needs_onnx
def test_without_onnxruntime_the_onnx_file_is_checked_by_onnx_reference_evaluator(tmp_path, capsys, monkeypatch):
    """No onnxruntime: onnx's reference evaluator runs the file before it is written; a file that does not
    reproduce the policy is refused (nothing written). The file written is then run by the real onnxruntime."""
    out = tmp_path / "waypoint.onnx"
    with monkeypatch.context() as patched:
        patched.setitem(sys.modules, "onnxruntime", None)  # import onnxruntime raises ImportError
        code, printed, errors = run_job(["--task", "EBoatWaypoint-v0", "--out", out], capsys)
        assert code == 0 and errors == [] and len(printed) == 1, (printed, errors)
        assert "onnx's reference evaluator reproduces the torch policy to " in printed[0], printed
        patched.setattr(policy_export, "TOLERANCE", -1.0)
        code, printed, errors = run_job(["--task", "EBoatWaypoint-v0", "--out", tmp_path / "refused.onnx"], capsys)
        assert code == 1 and len(errors) == 1 and "the exported onnx policy differs" in errors[0], errors
    assert sorted(p.name for p in tmp_path.iterdir()) == ["waypoint.onnx"]
    assert_reproduces(load_policy(shipped_policy_path("EBoatWaypoint-v0")), OnnxPolicy(out).act, 16, seed=7)


def test_an_export_that_does_not_reproduce_is_not_written(tmp_path, capsys, monkeypatch):
    """The check runs on the temporary file: a failing export leaves what was at --out untouched."""
    out = tmp_path / "p.pt"
    out.write_bytes(b"the previous export")
    monkeypatch.setattr(policy_export, "TOLERANCE", -1.0)
    code, printed, errors = run_job(["--task", "EBoatWaypoint-v0", "--out", out], capsys)
    assert code == 1 and printed == [] and len(errors) == 1, errors
    assert errors[0].startswith("ocean-warp export-policy: the exported torchscript policy differs")
    assert out.read_bytes() == b"the previous export" and sorted(p.name for p in tmp_path.iterdir()) == ["p.pt"]
    with pytest.raises(ExportError, match="nothing written"):
        export_torchscript(shipped_policy_path("EBoatWaypoint-v0"), tmp_path / "q.pt")


@needs_onnx
def test_the_runner_checks_shapes_and_values(exports):
    runner = OnnxPolicy(exports["EBoatWaypoint-v0"][1])
    one = np.full(5, 0.2)
    assert runner.act(one).shape == (3,) and runner.act(one).dtype == np.float32  # float64 in, float32 out
    assert runner.act([one.tolist()] * 4).shape == (4, 3)
    np.testing.assert_array_equal(runner.act(one), runner.act(one[None])[0])
    shape_error = r"^EBoatWaypoint-v0 policy: observation must have shape \(5,\) or \(B, 5\) with B >= 1, got "
    for bad in (np.zeros(6), np.zeros((2, 4)), np.zeros((0, 5)), np.zeros((1, 2, 5)), np.float32(1.0), []):
        with pytest.raises(ValueError, match=shape_error):
            runner.act(bad)
    with pytest.raises(ValueError, match=r"1 NaN or infinite value\(s\), first at row 1, value 3$"):
        runner.act(np.array([one, [0, 0, 0, np.nan, 0]]))
    with pytest.raises(ValueError, match="must be numbers"):
        runner.act(["a", "b", "c", "d", "e"])


@needs_onnx
def test_the_runner_refuses_other_files(tmp_path, exports):
    import onnx

    with pytest.raises(FileNotFoundError, match="no such file"):
        OnnxPolicy(tmp_path / "missing.onnx")
    (tmp_path / "text.onnx").write_text("not a model")
    with pytest.raises(ValueError, match="is not an ONNX model onnxruntime can run"):
        OnnxPolicy(tmp_path / "text.onnx")
    foreign = onnx.load(str(exports["EBoatWaypoint-v0"][1]))
    del foreign.metadata_props[:]
    onnx.save(foreign, str(tmp_path / "foreign.onnx"))
    with pytest.raises(ValueError, match=r"not an exported ocean_warp policy \(no 'format' entry"):
        OnnxPolicy(tmp_path / "foreign.onnx")


def test_the_runner_says_how_to_install_onnxruntime(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "onnxruntime", None)  # import onnxruntime raises ImportError
    with pytest.raises(ImportError, match=r"needs onnxruntime: pip install 'ocean-warp\[onnx\]'$"):
        OnnxPolicy(tmp_path / "policy.onnx")


@needs_onnx
def test_the_runner_loads_neither_torch_nor_warp(exports):
    """Loaded from its file it imports numpy and onnxruntime only; imported through the package it imports no
    torch (the package's __init__ imports Warp)."""
    path = exports["EBoatAvoid-v0"][1]
    standalone = f"""
import importlib.util, sys
spec = importlib.util.spec_from_file_location("onnx_policy", {onnx_policy.__file__!r})
module = importlib.util.module_from_spec(spec)
spec.loader.exec_module(module)
print(module.OnnxPolicy({str(path)!r}).act([0.0] * 6 + [1.0] * 24).shape)
print(sorted(name for name in ("torch", "warp", "ocean_warp") if name in sys.modules))
"""
    through_package = "import sys, ocean_warp.ros.onnx_policy; print('torch' in sys.modules)"
    run = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
           for code in (standalone, through_package)]
    assert [result.returncode for result in run] == [0, 0], [result.stderr for result in run]
    assert run[0].stdout.split("\n")[:2] == ["(3,)", "[]"] and run[1].stdout.strip() == "False"

