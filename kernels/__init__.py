"""Device code of ocean_warp: ``@wp.func`` and ``@wp.kernel`` only, grouped by physics; no state, no I/O.

Installed as ``ocean_warp.kernels``. Modules never import host code (``ocean_warp``).
"""
