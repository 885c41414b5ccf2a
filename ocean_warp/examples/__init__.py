"""Small runnable examples: ``python -m ocean_warp.examples.<name>``."""
