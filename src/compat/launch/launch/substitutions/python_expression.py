"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import PythonExpression

__all__ = ['PythonExpression']
