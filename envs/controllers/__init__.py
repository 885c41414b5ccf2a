"""Classical controllers that sail any task in place of a policy:

- ``sailing_autopilot``: ``SailingAutopilot`` and ``AutopilotConfig`` (line-of-sight guidance, beats with
  tacks at the laylines, sheet trim, heading control; ``AutopilotConfig.sail_only()`` without the motor),
  and on a task with a lidar (EBoatAvoid-v0) reactive obstacle avoidance: collision cones about the lidar's
  nearest return per sector (``LidarSectors``) turn each target into a steering target.
- ``autopilot_kernels``: its Warp kernels, one decision for every boat.
"""
