"""The environment's ROS side: ``ocean-warp ros`` (``node``, ``node_options``), the rosbag2 MCAP log of an
env's boats (``mcap_log``, with ``command_tap``, the hook that keeps each decision's commands) and
``ocean-warp export-policy`` (``policy_export``, ``policy_export_options``). The pieces that need no
environment (message definitions, topics from arrays, the ROS 1 and 2 buses, the ONNX policy runner) live in
the core's ``ocean_warp.ros``."""
