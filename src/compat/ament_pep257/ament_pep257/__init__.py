"""ament_pep257: PEP 257 docstring checks as ament configures them, run here with ruff."""
