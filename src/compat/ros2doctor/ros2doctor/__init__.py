"""`ros2 doctor` (alias `ros2 wtf`): checks of this ROS 2 setup, and reports on it."""
