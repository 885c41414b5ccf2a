"""The jobs people run, and their pieces:

- ``evaluation``: ``ocean-warp eval`` (a task sailed many times, policy against autopilot: CSVs and a PNG), the
  command line over ``ocean_warp.envs.evaluation``.
- ``demo``: ``ocean-warp demo`` (a fleet sails BCDACA; USD stage, PNGs, table), with ``demo_stage``.
- ``usd_export``: ``ocean-warp export-usd`` (a scenario recorded to a USD stage).
- ``fleet_scenario``: the fleet, sea and wind that the demo and the export share.
- ``success_rate``: a policy's success rate on a task from each environment's first episode.
"""
