"""The task specs (ocean_warp.envs.task_specs): one per task, read by the registry, the training presets and
the shipped policies; a new task is one entry."""

from __future__ import annotations

import pathlib
import subprocess
import sys

import gymnasium as gym
import pytest

from ocean_warp.envs.vrx import VrxTaskConfig

from ocean_warp.envs import TASK_IDS, MissionConfig, TaskConfig, make_task_config, register_envs, task_specs
from ocean_warp.envs.registration import task_name
from ocean_warp.envs.task_specs import TASK_SPECS, Deferred, TaskSpec, task_spec
from ocean_warp.envs.training import policies
from ocean_warp.envs.training.agents import TrainConfig, agent_config

POLICY_FOLDER = pathlib.Path(policies.__file__).resolve().parent


@pytest.mark.parametrize("spec", TASK_SPECS, ids=[spec.id for spec in TASK_SPECS])
def test_every_spec_is_whole(spec):
    """Each spec's id is a registered task's (gymnasium knows it with the namespace), its config factory gives
    a task config an env sails (the one make_task_config gives for the id), its training config is for its own id
    and trains on such a config, and its policy file is there where it names one (else none is shipped)."""
    assert spec.id in TASK_IDS and f"ocean_warp/{spec.id}" in gym.registry
    config = spec.make_config()
    assert isinstance(config, (TaskConfig, VrxTaskConfig))
    assert make_task_config(spec.id) == config and make_task_config(f"ocean_warp/{spec.id}") == config
    train = agent_config(spec.id)
    assert isinstance(train, TrainConfig) and train.task == spec.id and isinstance(train.train_task, (TaskConfig, VrxTaskConfig))
    if spec.policy_file is None:
        assert spec.id not in policies.SHIPPED_POLICIES
        with pytest.raises(ValueError, match="no policy is shipped"):
            policies.shipped_policy_path(spec.id)
    else:
        assert policies.SHIPPED_POLICIES[spec.id] == spec.policy_file
        assert policies.shipped_policy_path(spec.id) == POLICY_FOLDER / spec.policy_file
        assert (POLICY_FOLDER / spec.policy_file).is_file()


def test_the_three_tables_are_the_specs():
    """TASK_IDS is the specs' ids in order, each once; the shipped policies are the specs that name a file; the
    six E-Boat tasks and the mission's policy file are as published."""
    assert TASK_IDS == tuple(spec.id for spec in TASK_SPECS) and len(set(TASK_IDS)) == len(TASK_IDS)
    assert set(TASK_IDS) >= {"EBoatWaypoint-v0", "EBoatWaypointPlus-v0", "EBoatMission-v0", "EBoatMissionSail-v0",
                             "EBoatAvoid-v0", "EBoatAvoidSail-v0"}
    assert policies.SHIPPED_POLICIES == {s.id: s.policy_file for s in TASK_SPECS if s.policy_file is not None}
    assert task_spec("EBoatMission-v0").policy_file == "eboat_mission.pt"
    assert type(task_spec("ocean_warp/EBoatMissionSail-v0").make_config()).__name__ == "MissionSailConfig"


def test_an_unknown_id_is_one_line():
    for lookup in (task_spec, task_name, make_task_config, agent_config):
        with pytest.raises(ValueError) as error:
            lookup("EBoatNowhere-v0")
        message = str(error.value)
        assert "\n" not in message
        assert message.startswith("unknown task id 'EBoatNowhere-v0'; known: EBoatWaypoint-v0, ")


def test_a_new_task_is_one_spec(monkeypatch):
    """A throwaway spec added to TASK_SPECS alone (and taken out again): its id resolves, its config and its
    training config come from its factories, and register_envs registers it with gymnasium."""
    short = MissionConfig(episode_time=30.0)
    spec = TaskSpec("ThrowawayMission-v0", make_config=lambda: short,
                    make_agent_config=lambda: TrainConfig(task="ThrowawayMission-v0", train_task=short, iterations=3),
                    policy_file=None, description="the mission, 30 s long (a test's)")
    monkeypatch.setattr(task_specs, "TASK_SPECS", (*TASK_SPECS, spec))
    try:
        assert task_name("ocean_warp/ThrowawayMission-v0") == "ThrowawayMission-v0"
        assert make_task_config("ThrowawayMission-v0").episode_time == 30.0
        assert make_task_config("ThrowawayMission-v0", max_episode_steps=4).episode_time == 4 * short.decision_period
        assert agent_config("ocean_warp/ThrowawayMission-v0").iterations == 3
        register_envs()
        assert gym.registry["ocean_warp/ThrowawayMission-v0"].kwargs == {"task": "ThrowawayMission-v0"}
    finally:
        gym.registry.pop("ocean_warp/ThrowawayMission-v0", None)
    monkeypatch.undo()
    with pytest.raises(ValueError, match="unknown task id 'ThrowawayMission-v0'"):
        task_spec("ThrowawayMission-v0")


@pytest.mark.parametrize("fields, wrong", [
    (dict(id="ocean_warp/EBoatX-v0"), "TaskSpec.id"),
    (dict(id=""), "TaskSpec.id"),
    (dict(make_config="MissionConfig"), "make_config"),
    (dict(make_agent_config=None), "make_agent_config"),
    (dict(policy_file="policy.onnx"), "policy_file"),
    (dict(policy_file="sub/policy.pt"), "policy_file"),
    (dict(description="two\nlines"), "description"),
    (dict(description=" "), "description"),
])
def test_a_bad_spec_is_one_line(fields, wrong):
    good = dict(id="EBoatX-v0", make_config=MissionConfig, make_agent_config=MissionConfig, policy_file=None,
                description="a task")
    with pytest.raises(ValueError, match=wrong) as error:
        TaskSpec(**{**good, **fields})
    assert "\n" not in str(error.value)


def test_deferred_imports_on_call():
    """A Deferred names its factory without importing it; calling it imports the module and calls the name."""
    factory = Deferred("json.decoder", "JSONDecoder")
    assert type(factory()).__name__ == "JSONDecoder"
    code = ("import sys\nimport ocean_warp.envs.task_specs\n"
            "print(*(m in sys.modules for m in ('warp', 'torch', 'ocean_warp.envs.tasks.task_configs')))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["False", "False", "False"]
