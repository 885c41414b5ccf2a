"""Reinforcement-learning environments on top of the ocean_warp Simulator (installed as ``ocean_warp.envs``).

Empty for now: batched tasks, the rsl-rl VecEnv and gymnasium environments come with later issues.
"""
