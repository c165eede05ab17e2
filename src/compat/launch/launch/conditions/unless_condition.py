"""Upstream's module path; implemented in launch.conditions."""

from launch.conditions import UnlessCondition

__all__ = ['UnlessCondition']
