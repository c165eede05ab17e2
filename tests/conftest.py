import os

import pytest

# Set before any rclpy context exists in this process.
os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'

from ros_harness import RosHarness


@pytest.fixture
def ros():
    """Processes and a probe node in a ROS domain that no other test or run shares."""
    harness = RosHarness()
    try:
        yield harness
    finally:
        harness.close()
