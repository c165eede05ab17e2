"""Upstream's module path; implemented in launch_ros.actions.composable_node_container."""

from launch_ros.actions.composable_node_container import LoadComposableNodes

__all__ = ['LoadComposableNodes']
