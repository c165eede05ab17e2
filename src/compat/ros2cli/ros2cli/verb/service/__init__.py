"""The verbs of `ros2 service` (entry point group 'ros2service.verb'), one module each."""
