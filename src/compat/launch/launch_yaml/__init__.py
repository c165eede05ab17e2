"""YAML launch files (the parser itself lives in launch.frontend)."""
