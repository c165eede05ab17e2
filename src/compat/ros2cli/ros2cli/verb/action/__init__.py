"""The verbs of `ros2 action` (entry point group 'ros2action.verb'), one module each."""
