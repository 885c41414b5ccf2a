"""Training and the policies it makes:

- ``train_loop``: ``train()`` and ``ocean-warp train`` (rsl-rl PPO with the curriculum, seeded resets,
  progress, TensorBoard and atomic checkpoints).
- ``agents``: each task's ``TrainConfig`` (PPO, networks, observation groups).
- ``distributed`` and ``distributed_launch``: one policy trained by several ranks (torchrun); ``rendezvous``:
  how several hosts meet (``--nnodes``); ``train``: what torchrun starts on every rank
  (``python -m ocean_warp.envs.training.train``).
- ``policy_io``: checkpoints, and the exported actor (``policy.pt``) that evaluation and the demo load.
- ``policies/``: the policies shipped with ocean_warp.
"""
