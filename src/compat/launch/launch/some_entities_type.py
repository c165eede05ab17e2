"""Upstream's module path; implemented in launch.event_handler."""

from launch.event_handler import SomeEntitiesType, SomeEntitiesType_types_tuple

__all__ = ['SomeEntitiesType', 'SomeEntitiesType_types_tuple']
