"""``python -m ocean_warp.envs.training.train``: ``ocean-warp train`` as a module, so that torchrun can start it
once per rank.

    torchrun --standalone --nproc_per_node=2 -m ocean_warp.envs.training.train --task EBoatMission-v0 --minutes 5
    python -m ocean_warp.envs.training.train --help     # the options of ocean-warp train

(``ocean-warp train --gpus 2 ...`` starts exactly this for you.) An exception that escapes is recorded for
torchrun (``torch.distributed.elastic``'s ``record``), whose failure summary then shows it.
"""

from __future__ import annotations

import sys

from torch.distributed.elastic.multiprocessing.errors import record


@record
def main(argv: list[str] | None = None) -> int:
    import warp as wp

    from ocean_warp.envs.training.train_loop import main as train_main

    wp.config.log_level = wp.LOG_WARNING  # as ocean-warp does: no banner and module-load lines from every rank

    return train_main(argv)


if __name__ == "__main__":
    from ocean_warp.termination import exit_cleanly_on_sigterm

    exit_cleanly_on_sigterm(["train"])  # each rank: SIGTERM (torchrun passes it on) saves and exits 143
    try:
        status = main()
    except KeyboardInterrupt:
        # Every file is written atomically: what was written before Ctrl-C is whole.
        print("ocean-warp train: interrupted; files written before it are complete", file=sys.stderr)
        sys.exit(130)
    sys.exit(status)
