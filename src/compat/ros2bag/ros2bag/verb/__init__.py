"""The verbs of `ros2 bag` (entry point group 'ros2bag.verb'): record, info, play."""
