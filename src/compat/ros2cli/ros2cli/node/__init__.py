"""How a `ros2` verb sees the ROS graph: a direct rclpy node or the daemon's warm cache."""
