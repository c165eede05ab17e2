"""Upstream's module path; implemented in launch.substitution."""

from launch.substitution import normalize_to_list_of_substitutions

__all__ = ['normalize_to_list_of_substitutions']
