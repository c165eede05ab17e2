"""Upstream's module path; implemented in launch.utilities.type_utils."""

from launch.utilities.type_utils import (
    get_typed_value,
)

__all__ = ['get_typed_value']
