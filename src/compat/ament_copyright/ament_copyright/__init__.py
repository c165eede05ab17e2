"""ament_copyright: source files carry a copyright notice and a known license."""
