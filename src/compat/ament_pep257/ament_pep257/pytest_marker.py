"""pytest plugin: registers the `pep257` marker of ament_pep257's generated tests."""

import pytest


def pytest_configure(config: pytest.Config) -> None:
    """Declare the marker, so `-m pep257` selects the docstring test."""
    config.addinivalue_line('markers', 'pep257: a test that checks docstrings against PEP 257')
