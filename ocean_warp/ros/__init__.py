"""The robot's side, without an environment: ROS message definitions, topics built from the simulator's
arrays, the ROS 1 and ROS 2 buses, the node's loop, geodesy and the ONNX policy runner for the boat's
computer. Every part here is an optional extra; the rest of the core never imports this package. What needs
an environment (``ocean-warp ros``, the MCAP log of an env, ``ocean-warp export-policy``) lives in
``ocean_warp.envs.ros``."""
