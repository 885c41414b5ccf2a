"""Classical controllers that sail any task in place of a policy:

- ``line_following``: ``LineFollower`` and ``LineFollowingConfig``, the line following of Jaulin and Le Bars
  (2012), the default baseline of every task (``AutopilotController`` in ``ocean_warp.envs.evaluation``);
  ``line_following_kernels``: its law as Warp functions and its kernel.
- ``sailing_autopilot``: the legacy ``SailingAutopilot`` and ``AutopilotConfig`` (line-of-sight guidance, beats
  with tacks at the laylines, sheet trim, heading control; ``AutopilotConfig.sail_only()`` without the motor),
  and on a task with a lidar (EBoatAvoid-v0) reactive obstacle avoidance: collision cones about the lidar's
  nearest return per sector (``LidarSectors``) turn each target into a steering target.
- ``autopilot_kernels``: its Warp kernels, one decision for every boat.

For the WAM-V (two stern thrusters, fixed or azimuthing), batched in torch:

- ``station_keeping``: ``StationKeepingController`` and ``StationKeepingConfig``, PID station keeping on the
  goal pose, the earlier baseline of VRX's station-keeping task;
- ``los_guidance``: ``LosGuidanceController`` and ``LosGuidanceConfig``, line-of-sight guidance along the
  route, the earlier baseline of VRX's wayfinding and follow-path tasks;
- ``pivot_station_keeping``: ``PivotStationKeepingController`` and ``PivotStationKeepingConfig``, station keeping
  for fixed thrusters in transit, back-and-fill and holding modes, the default baseline of VRX's station-keeping
  and wayfinding tasks;
- ``gate_guidance``: ``GateGuidanceController`` and ``GateGuidanceConfig``, LOS guidance through the gates along
  their axes, clear of the buoys by collision cones, the default baseline of VRX's follow-path task;
- ``thrust_allocation``: ``ThrusterLayout`` and the force and moment -> thruster actions mappings they share.
"""
