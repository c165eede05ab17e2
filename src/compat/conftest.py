"""Fixtures the compat packages' unit tests share."""

import os
from collections.abc import Iterator
from pathlib import Path

import pytest


@pytest.fixture
def isolated_launch(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """Launch's logs under tmp_path; the environment a launch changes is restored afterwards.

    The launch and launch_ros test modules use it for every test (pytestmark).
    """
    monkeypatch.setenv('ROS_LOG_DIR', str(tmp_path / 'log'))
    saved = dict(os.environ)
    yield
    os.environ.clear()
    os.environ.update(saved)
