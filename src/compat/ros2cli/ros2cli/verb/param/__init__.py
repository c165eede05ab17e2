"""The verbs of `ros2 param` (entry point group 'ros2param.verb'), one module each."""
