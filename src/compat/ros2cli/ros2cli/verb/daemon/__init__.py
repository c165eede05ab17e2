"""The verbs of `ros2 daemon` (entry point group 'ros2cli.daemon.verb'), one module each."""
