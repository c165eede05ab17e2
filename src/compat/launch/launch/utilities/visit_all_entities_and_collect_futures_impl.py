"""Visiting an entity and everything it yields, as LaunchService does with what it is given."""

from __future__ import annotations

import asyncio

from launch.launch_context import LaunchContext
from launch.launch_description_entity import LaunchDescriptionEntity

EntityFutures = list[tuple[LaunchDescriptionEntity, asyncio.Future]]


def visit_all_entities_and_collect_futures(entity: LaunchDescriptionEntity,
                                           context: LaunchContext) -> EntityFutures:
    """Visit entity, then depth first and in order what its visit returns; the futures they give.

    Each entity's future (get_asyncio_future(), when not None) comes before those of the entities
    its visit returned. Something that is not an entity is a TypeError naming it.
    """
    found: EntityFutures = []
    visit_entities_into(entity, context, found)
    return found


def visit_entities_into(entity: LaunchDescriptionEntity, context: LaunchContext,
                        found: EntityFutures) -> None:
    """visit_all_entities_and_collect_futures, adding to found as it goes.

    LaunchService keeps its futures this way: when a later visit raises, the processes and timers
    already started are still waited for and stopped.
    """
    if not isinstance(entity, LaunchDescriptionEntity):
        raise TypeError(f"expected a launch description entity, got '{type(entity).__name__}': {entity!r}")
    sub_entities = entity.visit(context)
    future = entity.get_asyncio_future()
    if future is not None:
        found.append((entity, future))
    for sub_entity in sub_entities or []:
        visit_entities_into(sub_entity, context, found)
