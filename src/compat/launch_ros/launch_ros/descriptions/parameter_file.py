"""Upstream's module path; implemented in launch_ros.parameter_descriptions."""

from launch_ros.parameter_descriptions import ParameterFile

__all__ = ['ParameterFile']
