"""Types by name, including a service's event type ('example_interfaces/srv/AddTwoInts_Event')."""

from __future__ import annotations

import importlib
from typing import Any


def import_type(type_name: str) -> Any:
    """The generated class of 'pkg/msg/Type' or 'pkg/srv/Service_Event' (also _Request, _Response).

    ValueError says why a name does not resolve.
    """
    parts = type_name.split('/')
    if len(parts) != 3 or not all(parts):
        raise ValueError(f"'{type_name}' is not a type name like 'std_msgs/msg/String'")
    package, kind, name = parts
    try:
        module = importlib.import_module(f'{package}.{kind}')
    except ImportError:
        raise ValueError(f"no interface package '{package}' with {kind} types is installed") from None
    if hasattr(module, name):
        return getattr(module, name)
    base, _, part = name.rpartition('_')
    if part in ('Request', 'Response', 'Event') and hasattr(module, base):
        return getattr(getattr(module, base), part)
    raise ValueError(f"'{package}' has no {kind} type '{name}'")


def qos_yaml(qos: Any) -> dict[str, Any]:
    """A publisher's QoS profile as rosbag2's metadata writes it (durations as sec/nsec)."""
    from ros2bag.bag import duration_yaml

    return {
        'history': qos.history.name.lower(),
        'depth': qos.depth,
        'reliability': qos.reliability.name.lower(),
        'durability': qos.durability.name.lower(),
        'deadline': duration_yaml(qos.deadline.nanoseconds),
        'lifespan': duration_yaml(qos.lifespan.nanoseconds),
        'liveliness': qos.liveliness.name.lower(),
        'liveliness_lease_duration': duration_yaml(qos.liveliness_lease_duration.nanoseconds),
        'avoid_ros_namespace_conventions': bool(qos.avoid_ros_namespace_conventions),
    }
