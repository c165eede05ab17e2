"""LaunchIntrospector: a launch description as an indented tree of what it would do."""

from __future__ import annotations

from collections.abc import Iterable

from launch.launch_description import LaunchDescription
from launch.launch_description_entity import LaunchDescriptionEntity

__all__ = ['LaunchIntrospector', 'format_entities']


def format_entities(entities: Iterable[LaunchDescriptionEntity], depth: int = 0) -> list[str]:
    """One line per entity, its sub-entities indented under it (conditional ones under a note)."""
    lines = []
    for entity in entities:
        lines.append('    ' * depth + '├── ' + entity.describe())
        lines += format_entities(entity.describe_sub_entities(), depth + 1)
        for description, sub_entities in entity.describe_conditional_sub_entities():
            lines.append('    ' * (depth + 1) + f'({description})')
            lines += format_entities(sub_entities, depth + 2)
    return lines


class LaunchIntrospector:
    """Describes launch descriptions without running them (what `ros2 launch -p` prints)."""

    def format_launch_description(self, launch_description: LaunchDescription,
                                  title: str = '<launch.LaunchDescription>') -> str:
        return '\n'.join([title, *format_entities(launch_description.entities)])
