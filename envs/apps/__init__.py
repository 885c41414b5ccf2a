"""The jobs people run, and their pieces:

- ``evaluation``: ``ocean-warp eval`` (a task sailed many times, policy against autopilot: CSVs and a PNG).
- ``demo``: ``ocean-warp demo`` (a fleet sails BCDACA; USD stage, PNGs, table), with ``demo_stage``.
- ``usd_export``: ``ocean-warp export-usd`` (a scenario recorded to a USD stage).
- ``fleet_scenario``: the fleet, sea and wind that the demo and the export share.
- ``mission_metrics`` and ``mission_plot``: what a mission run measures (times, tacks, cross-track spread)
  and draws.
- ``success_rate``: a policy's success rate on a task from each environment's first episode.
"""
