"""Upstream's module path; implemented in launch.conditions."""

from launch.conditions import evaluate_condition_expression

__all__ = ['evaluate_condition_expression']
