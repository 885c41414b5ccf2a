"""The ``ocean-warp`` command: ``ocean-warp <job> [options]``; ``ocean-warp <job> --help`` for a job's options.

Each job's options live in a light module (its parser, no Warp or torch), so ``--help``, ``--help-long``
and a mistyped option answer before the simulator loads; the job's own module is imported only once its
options parse.
"""

from __future__ import annotations

import argparse
import sys

from .cli_support import COMMAND, JobArgumentParser, RawDescriptionHelpFormatter
from .termination import exit_cleanly_on_sigterm

JOBS = {
    "demo": ("ocean_warp.envs.apps.demo", "ocean_warp.envs.apps.demo_options",
             "a fleet sails the BCDACA mission in waves (policy and autopilot): USD stage, PNGs, table"),
    "ocean": ("ocean_warp.examples.ocean_snapshot", "ocean_warp.examples.ocean_snapshot_options",
              "a JONSWAP sea: height field and spectrum PNGs"),
    "drop-hulls": ("ocean_warp.examples.drop_hulls", "ocean_warp.examples.drop_hulls_options",
                   "hulls of several shapes dropped into waves: heave and roll"),
    "train": ("ocean_warp.envs.training.train_loop", "ocean_warp.envs.training.train_options",
              "train a sailing policy with rsl-rl PPO (progress, TensorBoard, checkpoints)"),
    "polar": ("ocean_warp.examples.polar_chart", "ocean_warp.examples.polar_chart_options",
              "the E-Boat's speed polar for true wind 4, 7 and 10 m/s: PNG and CSV"),
    "eval": ("ocean_warp.envs.apps.evaluation", "ocean_warp.envs.apps.evaluation_options",
             "a task sailed many times in waves, policy vs autopilot: PNG and CSVs"),
    "export-usd": ("ocean_warp.envs.apps.usd_export", "ocean_warp.envs.apps.usd_export_options",
                   "record a scenario (boats, sea, wind, controller, duration) to a USD stage"),
    "render": ("ocean_warp.envs.apps.render", "ocean_warp.envs.apps.render_options",
               "a video (MP4 or GIF) of a fleet's run, ray-traced from a chase or fixed camera"),
    "ros": ("ocean_warp.envs.ros.node", "ocean_warp.envs.ros.node_options",
            "the simulator as a ROS node: the seed's topics and standard ones, commands, a reset service"),
    "export-policy": ("ocean_warp.envs.ros.policy_export", "ocean_warp.envs.ros.policy_export_options",
                      "a policy checkpoint as ONNX or TorchScript, its observation normalisation inside"),
    "bem": ("ocean_warp.seakeeping.bem_command", "ocean_warp.seakeeping.bem_options",
            "a hull's added mass, damping and radiation fits from potential flow (capytaine): JSON"),
}
"""Each job: the module whose ``main(argv)`` runs it, the light module whose ``parser()`` builds its options
(and, where the job takes arguments that are not options, whose ``own_arguments(argv)`` picks the options),
and what it does, in a line."""


def version() -> str:
    """The installed distribution's version; the package's own where it is not installed."""
    from importlib import metadata

    try:
        return metadata.version("ocean-warp")
    except metadata.PackageNotFoundError:
        from . import __version__

        return __version__


def _parser() -> argparse.ArgumentParser:
    width = max(len(name) for name in JOBS)
    jobs = "\n".join(f"  {name:<{width}}  {text}" for name, (_, _, text) in JOBS.items())
    parser = JobArgumentParser(
        prog=COMMAND, formatter_class=RawDescriptionHelpFormatter,
        description="ocean_warp's jobs: `ocean-warp <job> [options]`; `ocean-warp <job> --help` gives a job's\n"
                    "options with their defaults and units, `ocean-warp <job> --help-long` what it does in detail.",
        epilog=f"jobs:\n{jobs}")
    parser.add_argument("--version", action="version", version=f"{COMMAND} {version()}")
    parser.add_argument("job", choices=list(JOBS), metavar="job", help="one of the jobs below")
    return parser


def _run(argv: list[str]) -> int:
    """Parse the job and its options (light modules only), then load the job's module and run it."""
    import importlib

    args, rest = _parser().parse_known_args(argv[:1])
    job_module, options_module, _ = JOBS[args.job]
    options = importlib.import_module(options_module)
    own = getattr(options, "own_arguments", list)  # ros: all but rospy's name:=value remaps
    options.parser().parse_args(own(argv[1:] + rest))  # --help and --help-long, or exit 2 on a typo
    import warp as wp

    from .devices import init_warp

    wp.config.log_level = wp.LOG_WARNING  # Warp's banner and module-load lines would bury the summary
    init_warp()  # without the no-driver warning Warp would print on a machine without a GPU
    return importlib.import_module(job_module).main(argv[1:] + rest) or 0


def main(argv=None) -> None:
    """``ocean-warp``: exits with the job's status; Ctrl-C at any moment (the imports included) is one line and
    status 130."""
    argv = sys.argv[1:] if argv is None else list(argv)
    job = argv[0] if argv and argv[0] in JOBS else None
    exit_cleanly_on_sigterm(argv)
    try:
        code = _run(argv)
    except KeyboardInterrupt:
        # Every file is written atomically: what was written before Ctrl-C is whole, nothing is half-written.
        print(f"{COMMAND}{f' {job}' if job else ''}: interrupted; files written before it are complete",
              file=sys.stderr)
        sys.exit(130)
    if code:
        sys.exit(code)


if __name__ == "__main__":
    main()
