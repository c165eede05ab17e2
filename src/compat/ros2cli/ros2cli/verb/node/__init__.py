"""The verbs of `ros2 node` (entry point group 'ros2node.verb'), one module each."""
