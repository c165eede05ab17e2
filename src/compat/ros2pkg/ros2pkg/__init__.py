"""`ros2 pkg`: find installed packages and create new ones."""
