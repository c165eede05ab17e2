"""pytest plugin: registers the `copyright` marker of ament_copyright's generated tests."""

import pytest


def pytest_configure(config: pytest.Config) -> None:
    """Declare the marker, so `-m copyright` selects the header test."""
    config.addinivalue_line(
        'markers', 'copyright: a test that checks non-empty source files for a copyright and license')
