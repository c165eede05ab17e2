"""pytest plugin: registers the `linter` marker that every ament linter test carries."""

import pytest


def pytest_configure(config: pytest.Config) -> None:
    """Declare the marker, so `-m linter` selects lint tests and --strict-markers accepts it."""
    config.addinivalue_line('markers', 'linter: a test that runs one of ament\'s code linters')
