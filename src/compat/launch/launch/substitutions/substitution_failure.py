"""Upstream's module path; implemented in launch.substitution."""

from launch.substitution import SubstitutionFailure

__all__ = ['SubstitutionFailure']
