"""`owl check`: the course's exercises checked over real ROS 2, one plug-in per course section."""
