"""Upstream's module path; implemented in launch_ros.actions.scoped."""

from launch_ros.actions.scoped import PushROSNamespace, PushRosNamespace

__all__ = ['PushROSNamespace', 'PushRosNamespace']
