"""ros2launch: the `ros2 launch` command."""
