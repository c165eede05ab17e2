"""Upstream's module path; implemented in launch.frontend."""

from launch.frontend import parse_substitution

__all__ = ['parse_substitution']
