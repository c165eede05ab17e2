"""The verbs of `ros2 interface` (entry point group 'ros2interface.verb'), one module each."""
