"""rqt in a browser: the four rqt plugins of the Owl Kit course, served by one rclpy node."""
