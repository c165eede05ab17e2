"""The verbs of `ros2 pkg` (entry point group 'ros2pkg.verb'), one module each."""
