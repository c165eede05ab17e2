"""pytest plugin: registers the `flake8` marker of ament_flake8's generated tests."""

import pytest


def pytest_configure(config: pytest.Config) -> None:
    """Declare the marker, so `-m flake8` selects the code style test."""
    config.addinivalue_line('markers', 'flake8: a test that checks the code against ament_flake8')
