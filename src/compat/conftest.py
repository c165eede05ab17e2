"""Fixtures the compat packages' unit tests share."""

import os

import pytest


@pytest.fixture
def isolated_launch(tmp_path, monkeypatch):
    """Launch's logs under tmp_path; the environment a launch changes is restored afterwards.

    The launch and launch_ros test modules use it for every test (pytestmark).
    """
    monkeypatch.setenv('ROS_LOG_DIR', str(tmp_path / 'log'))
    saved = dict(os.environ)
    yield
    os.environ.clear()
    os.environ.update(saved)
