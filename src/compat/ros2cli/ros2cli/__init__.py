"""The `ros2` command line tool of Owl Kit Lab."""
