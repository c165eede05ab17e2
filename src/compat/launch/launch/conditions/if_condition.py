"""Upstream's module path; implemented in launch.conditions."""

from launch.conditions import IfCondition

__all__ = ['IfCondition']
