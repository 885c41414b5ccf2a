"""``ocean-warp export-policy``'s options: its parser, light to import (no torch, no onnx), so that ``--help``
and a mistyped option answer at once. The job itself is ``policy_export``."""

from __future__ import annotations

import argparse

from ocean_warp.cli_support import job_parser
from ocean_warp.envs.registration import DEFAULT_TASK

__all__ = ["OUT_FOLDER", "parser"]

OUT_FOLDER = "out/export-policy"
"""Where the exported file goes without --out."""


def parser() -> argparse.ArgumentParser:
    """The parser of ``ocean-warp export-policy``."""
    parser = job_parser(
        "export-policy", "Export a policy checkpoint for the boat's computer, as ONNX (numpy and onnxruntime run "
        "it) or TorchScript, its observation normalisation inside and its metadata in the file; the file is "
        "checked against the torch policy before it is written.", long_help_from="ocean_warp.envs.ros.policy_export",
        examples=("ocean-warp export-policy --task EBoatMission-v0",
                  "ocean-warp export-policy --policy out/train/EBoatMission-v0/<date>_<name>/policy.pt "
                  "--out out/export-policy/boat.onnx",
                  "ocean-warp export-policy --task EBoatAvoid-v0 --format torchscript"))
    parser.add_argument("--policy", default=None, metavar="FILE",
                        help="policy checkpoint (ocean_warp.policy/1) to export (default: the shipped policy of "
                             "--task)")
    parser.add_argument("--task", default=None, metavar="ID",
                        help="a task id: without --policy, export its shipped policy; with --policy, the checkpoint "
                             f"must be for this task (default: the checkpoint's task; {DEFAULT_TASK} without "
                             "--policy)")
    parser.add_argument("--format", default=None, metavar="FORMAT",
                        help="onnx or torchscript (default: from --out's suffix, .onnx or .pt; onnx without --out)")
    parser.add_argument("--out", default=None, metavar="FILE",
                        help="the file to write, .onnx for onnx, .pt for torchscript (default: "
                             f"{OUT_FOLDER}/<checkpoint name>.onnx, or .torchscript.pt)")
    return parser
