"""ament_flake8: ament's flake8 rules for Python code, checked here with ruff."""
