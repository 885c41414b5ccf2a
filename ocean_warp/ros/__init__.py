"""The robot's side: the simulator as a ROS node, logs ROS tools read (rosbag2 MCAP), and policies exported
for the boat's computer (ONNX, TorchScript). Every part here is an optional extra; the core never imports
this package."""
