"""The `ros2 launch` command (entry point group 'ros2cli.command'): ros2launch.command.launch."""
