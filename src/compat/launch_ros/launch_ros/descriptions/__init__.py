"""Descriptions of launch_ros: parameters, and components (refused, see ComposableNodeContainer)."""

from launch_ros.actions.composable_node_container import ComposableNode
from launch_ros.parameter_descriptions import Parameter, ParameterFile, ParameterValue

__all__ = ['ComposableNode', 'Parameter', 'ParameterFile', 'ParameterValue']
