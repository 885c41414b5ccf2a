"""The ``ocean-warp`` command: ``ocean-warp <job> [options]``; ``ocean-warp <job> --help`` for a job's options."""

from __future__ import annotations

import argparse
import sys

from .termination import exit_cleanly_on_sigterm

JOBS = {
    "demo": ("ocean_warp.envs.apps.demo", "a fleet sails the BCDACA mission in waves (policy and autopilot): USD stage, "
             "PNGs, table"),
    "ocean": ("ocean_warp.examples.ocean_snapshot", "a JONSWAP sea: height field and spectrum PNGs"),
    "drop-hulls": ("ocean_warp.examples.drop_hulls", "hulls of several shapes dropped into waves: heave and roll"),
    "train": ("ocean_warp.envs.training.train_loop", "train a sailing policy with rsl-rl PPO (progress, TensorBoard, checkpoints)"),
    "polar": ("ocean_warp.examples.polar_chart", "the E-Boat's speed polar for true wind 4, 7 and 10 m/s: PNG and CSV"),
    "eval": ("ocean_warp.envs.apps.evaluation", "a task sailed many times in waves, policy vs autopilot: PNG and CSV "
             "(--task ID: any registered task; default the BCDACA mission, 20 runs)"),
    "export-usd": ("ocean_warp.envs.apps.usd_export", "record a scenario (boats, sea, wind, controller, duration) to a "
                   "USD stage"),
    "render": ("ocean_warp.envs.apps.render", "a video (MP4 or GIF) of a fleet's run, ray-traced from a chase or fixed "
               "camera"),
    "ros": ("ocean_warp.ros.node", "the simulator as a ROS 1 node: the seed's topics and standard ones, commands, a reset "
            "service (Debian's ros-core and python3-rospy)"),
    "export-policy": ("ocean_warp.ros.policy_export", "a policy checkpoint as ONNX or TorchScript, its observation "
                      "normalisation inside (the onnx extra for ONNX)"),
}


def main(argv=None) -> None:
    argv = sys.argv[1:] if argv is None else list(argv)
    exit_cleanly_on_sigterm(argv)
    parser = argparse.ArgumentParser(
        prog="ocean-warp", description="ocean_warp's jobs: `ocean-warp <job> [options]`; `ocean-warp <job> --help` "
        "gives a job's options with their defaults and units.")
    parser.add_argument("job", choices=sorted(JOBS), help="; ".join(f"{name}: {text}" for name, (_, text) in JOBS.items()))
    args, rest = parser.parse_known_args(argv[:1])
    import warp as wp

    from .devices import init_warp

    wp.config.log_level = wp.LOG_WARNING  # Warp's banner and module-load lines would bury the summary
    init_warp()  # without the no-driver warning Warp would print on a machine without a GPU
    module_name = JOBS[args.job][0]
    module = __import__(module_name, fromlist=["main"])
    try:
        code = module.main(argv[1:] + rest)
    except KeyboardInterrupt:
        # Every file is written atomically: what was written before Ctrl-C is whole, nothing is half-written.
        print(f"ocean-warp {args.job}: interrupted; files written before it are complete", file=sys.stderr)
        sys.exit(130)
    if code:
        sys.exit(code)


if __name__ == "__main__":
    main()
