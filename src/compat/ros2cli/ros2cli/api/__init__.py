"""What the verbs of one `ros2` command share: a module per command (upstream's ros2<command>.api).

The modules import no rclpy, message package or YAML at their top: `ros2 <command> -h` imports
every verb of the command, and the verbs import these.
"""
