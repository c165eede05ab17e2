"""Upstream's module path; implemented in launch.frontend."""

from launch.frontend import Parser

__all__ = ['Parser']
