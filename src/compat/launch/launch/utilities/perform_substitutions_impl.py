"""Upstream's module path; implemented in launch.substitution."""

from launch.substitution import perform_substitutions

__all__ = ['perform_substitutions']
