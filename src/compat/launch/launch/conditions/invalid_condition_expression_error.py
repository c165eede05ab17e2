"""Upstream's module path; implemented in launch.conditions."""

from launch.conditions import InvalidConditionExpressionError

__all__ = ['InvalidConditionExpressionError']
