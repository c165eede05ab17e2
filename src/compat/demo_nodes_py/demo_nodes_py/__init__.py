"""The official ROS 2 demos' Python nodes (talker, listener, add_two_ints, introspection)."""
