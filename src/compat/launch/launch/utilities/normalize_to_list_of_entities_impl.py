"""normalize_to_list_of_entities: entities and groups of entities, as one flat list."""

from __future__ import annotations

from collections.abc import Iterable

from launch.launch_description_entity import LaunchDescriptionEntity
from launch.some_entities_type import SomeEntitiesType


def normalize_to_list_of_entities(entities: Iterable[SomeEntitiesType]) -> list[LaunchDescriptionEntity]:
    """Each item is an entity or an iterable of entities; the result flattens that one level."""
    flat: list[LaunchDescriptionEntity] = []
    for item in entities:
        if isinstance(item, LaunchDescriptionEntity):
            flat.append(item)
        elif isinstance(item, Iterable) and not isinstance(item, (str, bytes)):
            flat.extend(item)
        else:
            raise TypeError(f"expected a launch description entity or an iterable of them, got "
                            f"'{type(item).__name__}': {item!r}")
    return flat
