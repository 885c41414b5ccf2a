"""``ocean-warp demo``'s options: what the demo sails (:class:`DemoConfig`) and its parser, light to import
(no Warp, no torch), so that ``--help`` and a mistyped option answer at once. The job itself is ``demo``."""

from __future__ import annotations

import argparse
import dataclasses

from ocean_warp.cli_support import job_parser
from ocean_warp.validation import require_in_range, require_positive

from .scenario_options import FleetScenario, add_scenario_arguments, shipped_policy_or_none

__all__ = ["DemoConfig", "parser"]


@dataclasses.dataclass(frozen=True)
class DemoConfig(FleetScenario):
    """What the demo sails and records (see :class:`FleetScenario` for the fleet, sea and stage)."""

    ocean_resolution: int = 96
    """At most this many ocean mesh vertices along a side: the area grows where boats got lost, so the
    demo keeps the mesh finer than a plain scenario's 64 (a loop of 121 frames, a few MB)."""
    policy_share: float = 0.5
    """Fraction of the boats sailed by the task's shipped policy (the first ones); the rest by the autopilot
    (every boat, on a task without a shipped policy)."""
    time_limit: float = 1200.0
    """Per boat [s]; a boat still sailing then counts as timed out."""
    loop_period: float = 60.0
    """The sea repeats every this many seconds [s], so the stage holds one seamless loop of it."""
    usd: bool = True
    """Write the USD stage (and its preview)."""
    policy: str | None = None
    """A policy checkpoint (a ``policy.pt`` or ``model_<it>.pt`` that ``ocean-warp train`` wrote) that the
    policy's share of the boats sails; None: the task's shipped policy."""

    def __post_init__(self):
        super().__post_init__()
        owner = "DemoConfig"
        require_in_range(owner, "policy_share", self.policy_share, 0.0, 1.0)
        require_positive(owner, "time_limit", self.time_limit, unit=" [s]")
        require_positive(owner, "loop_period", self.loop_period, unit=" [s]")
        if not isinstance(self.usd, bool):
            raise ValueError(f"{owner}.usd must be True or False, got {self.usd!r}")

    @property
    def policy_boats(self) -> int:
        """Boats the policy sails: the policy's share, or 0 without --policy on a task without a shipped
        policy."""
        if self.policy is None and shipped_policy_or_none(self.task_id) is None:
            return 0
        return int(round(self.policy_share * self.boats))



def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp demo``."""
    defaults = DemoConfig()
    parser = job_parser("demo", "A fleet of E-Boats sails the BCDACA mission (or --task) in waves, half with the "
                        "shipped policy (or --policy) and half with the classical autopilot; writes a USD stage "
                        "with a preview PNG, trajectories.png and results.csv into --out.",
                        long_help_from="ocean_warp.envs.apps.demo",
                        examples=("ocean-warp demo", "ocean-warp demo --boats 4 --no-usd",
                                  "ocean-warp demo --policy out/train/EBoatMission-v0/<date>_<name>/policy.pt"))
    add_scenario_arguments(parser, defaults)
    parser.add_argument("--policy-share", type=float, default=defaults.policy_share,
                        help="fraction of the boats sailed by the policy (0-1)")
    parser.add_argument("--policy", default=None, metavar="FILE",
                        help="a policy checkpoint for the policy's share of the boats: a policy.pt or "
                             "model_<it>.pt that train wrote (default: the task's shipped policy)")
    parser.add_argument("--time-limit", type=float, default=defaults.time_limit, metavar="SECONDS",
                        help="per boat [s]")
    parser.add_argument("--loop-period", type=float, default=defaults.loop_period, metavar="SECONDS",
                        help="the sea repeats every this many seconds (one seamless loop in the stage)")
    parser.add_argument("--no-usd", action="store_true", help="skip the USD stage and its preview")
    parser.add_argument("--out", default="out/demo", help="folder for the stage, PNGs and tables")
    parser.add_argument("--record", default=None, metavar="FILE.mcap",
                        help="also write a rosbag2 MCAP log of the fleet, every boat under /eboat_<i> (needs the "
                             "mcap extra: pip install 'ocean-warp[mcap]')")
    return parser
