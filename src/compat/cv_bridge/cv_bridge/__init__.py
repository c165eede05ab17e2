"""ROS 2's cv_bridge Python API: `from cv_bridge import CvBridge, CvBridgeError`."""

from .core import CvBridge
from .error import CvBridgeError

__all__ = ['CvBridge', 'CvBridgeError']
