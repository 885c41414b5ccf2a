"""Classical controllers that sail any task in place of a policy:

- ``sailing_autopilot``: ``SailingAutopilot`` and ``AutopilotConfig`` (line-of-sight guidance, beats with
  tacks at the laylines, sheet trim, heading control; ``AutopilotConfig.sail_only()`` without the motor).
- ``autopilot_kernels``: its Warp kernels, one decision for every boat.
"""
