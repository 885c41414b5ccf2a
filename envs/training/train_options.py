"""``ocean-warp train``'s options: its parser, light to import (no Warp, torch or rsl-rl), so that ``--help``
and a mistyped option answer at once. The job itself is ``train_loop``."""

from __future__ import annotations

import argparse

from ocean_warp.cli_support import add_device_argument, job_parser

from ..registration import DEFAULT_TASK, TASK_IDS

__all__ = ["DEFAULT_TIMEOUT_S", "RUNS_ROOT", "parser"]

DEFAULT_TIMEOUT_S = 300.0
"""[s] How long a rank waits for the others in any collective (and at startup) before it gives up."""
RUNS_ROOT = "out/train"
"""The folder that holds every run's ``<task>/<date>_<name>/`` by default."""


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp train``."""
    parser = job_parser("train", "Train a sailing policy with rsl-rl PPO: a progress bar, TensorBoard logs, atomic "
                        "checkpoints and the exported policy.pt, in a run folder <task>/<date>_<name>/ under "
                        "--runs-root.",
                        long_help_from="ocean_warp.envs.training.train_loop",
                        examples=("ocean-warp train --minutes 20",
                                  "ocean-warp train --task EBoatWaypoint-v0 --device cpu --workers 2 --num-envs 512",
                                  "ocean-warp train --resume out/train/EBoatMission-v0/<date>_<name>/model_99.pt",
                                  "ocean-warp train --gpus 4 --nnodes 2 --rdzv-endpoint node01:29500  # on both hosts"))
    parser.add_argument("--task", default=DEFAULT_TASK, metavar="ID",
                        help=f"the task to train on: {', '.join(TASK_IDS)}, with or without 'ocean_warp/' "
                             f"(default {DEFAULT_TASK})")
    add_device_argument(parser)
    parser.add_argument("--torch-threads", type=int, default=None, metavar="N",
                        help="threads of torch's CPU operations in this process (default: 1 on the CPU, where the "
                             "small networks gain nothing from more and more threads contend with Warp's; torch's "
                             "own default on a GPU); --workers processes use one each")
    parser.add_argument("--num-envs", type=int, default=None,
                        help="parallel boats per process (rank) (default: the task's, 256 on the CPU, 4096 on a GPU)")
    length = parser.add_argument_group("how long (either, or both: the first reached ends it)")
    length.add_argument("--iterations", type=int, default=None, help="PPO iterations (default: the task's)")
    length.add_argument("--minutes", type=float, default=None, help="wall-time limit [minutes]")
    parser.add_argument("--seed", type=int, default=0, help="seed of environments, networks and sampling")
    parser.add_argument("--run-name", default=None, help="suffix of the run folder")
    parser.add_argument("--runs-root", default=RUNS_ROOT, help="folder that holds <task>/<date>_<name>/")
    parser.add_argument("--resume", default=None, metavar="PATH",
                        help="continue from a training checkpoint (model_<it>.pt), in its folder")
    parser.add_argument("--set", dest="overrides", action="append", default=[], metavar="FIELD=VALUE",
                        help="change a field of the task's TrainConfig, e.g. ppo.learning_rate=3e-4, "
                        "steps_per_env=32, train_task.decision_period=2.0 (repeatable)")
    parser.add_argument("--workers", type=int, default=1,
                        help="CPU only: simulate the environments in this many processes, one core each "
                        "(default 1: in this process)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    ranks = parser.add_argument_group("several GPUs and hosts (torchrun; see ocean_warp.envs.training.distributed)")
    ranks.add_argument("--gpus", default=None, metavar="G",
                       help="train one policy on G GPUs of this host: starts torchrun with G ranks, each with "
                       "--num-envs environments on its own GPU (default: this process, one device); with --nnodes, "
                       "G GPUs on every host")
    ranks.add_argument("--nnodes", default=None, metavar="N|MIN:MAX",
                       help="train on N hosts (or from MIN to MAX): run this same command on every host; each starts "
                       "torchrun with its ranks (--gpus G, else one on --device) and they meet at --rdzv-endpoint")
    ranks.add_argument("--node-rank", type=int, default=None, metavar="R",
                       help="with --nnodes N: this host's index, 0..N-1, so that host 0 (the --rdzv-endpoint host) "
                       "holds rank 0, which writes the files (default: torchrun's c10d rendezvous numbers the hosts)")
    ranks.add_argument("--rdzv-endpoint", default=None, metavar="HOST:PORT",
                       help="with --nnodes: where the hosts meet, one of them and a free port on it")
    ranks.add_argument("--rdzv-id", default=None, metavar="ID",
                       help="with --nnodes: the job's name at the rendezvous, the same on every host (default "
                       "ocean-warp-train; give concurrent jobs their own, e.g. $SLURM_JOB_ID)")
    ranks.add_argument("--dist-timeout", type=float, default=DEFAULT_TIMEOUT_S, metavar="SECONDS",
                       help="with several ranks: the longest a rank waits for the others before the job stops")
    return parser
