"""The faces the batched environment shows to RL libraries, all over the same ``SailingEnv`` buffers:

- ``rsl_rl_env``: ``RslRlVecEnv`` for rsl-rl (torch tensors, TensorDict observations).
- ``gym_env``: ``SailingVectorEnv`` and ``SailingEnvSingle`` for gymnasium (numpy copies), registered as
  ``ocean_warp/<task id>``.
- ``sb3_env``: ``Sb3VecEnv`` for stable-baselines3 (an optional extra, ``pip install -e ".[sb3]"``).
"""
