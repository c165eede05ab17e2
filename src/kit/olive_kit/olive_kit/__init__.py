"""The Owl Kit as data: its modules, namespaces, addresses, pages, topics and limits (no ROS)."""
