"""A rosdep for Owl Kit Lab: resolves keys to installed packages and pinned ROS wheels."""
