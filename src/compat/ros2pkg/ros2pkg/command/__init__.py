"""The `ros2 pkg` command (entry point group 'ros2cli.command'): ros2pkg.command.pkg."""
