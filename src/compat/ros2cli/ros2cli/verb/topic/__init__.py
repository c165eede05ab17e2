"""The verbs of `ros2 topic` (entry point group 'ros2topic.verb'), one module each."""
