"""Parallel backends for the CPU, where Warp runs a launch on one thread:

- ``sharded``: ``ShardedSailingEnv``, one batch of environments simulated by several worker processes (one
  core each), behind the same buffers as ``SailingEnv``.
- ``shared_ocean``: the one ocean the parent evaluates and every worker reads.
"""
