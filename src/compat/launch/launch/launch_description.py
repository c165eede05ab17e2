"""LaunchDescription: the list of entities a launch file returns."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from launch.action import Action
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.logging import get_logger

if TYPE_CHECKING:
    from launch.actions.declare_launch_argument import DeclareLaunchArgument
    from launch.launch_context import LaunchContext


class LaunchDescription(LaunchDescriptionEntity):
    """Entities visited in order; the arguments it declares are discoverable without running it."""

    def __init__(self, initial_entities: Iterable[LaunchDescriptionEntity] | None = None, *,
                 deprecated_reason: str | None = None) -> None:
        self.__entities = list(initial_entities or [])
        for entity in self.__entities:
            _check_entity(entity)
        self.__deprecated_reason = deprecated_reason

    @property
    def entities(self) -> list[LaunchDescriptionEntity]:
        return self.__entities

    @property
    def deprecated(self) -> bool:
        return self.__deprecated_reason is not None

    @property
    def deprecated_reason(self) -> str | None:
        return self.__deprecated_reason

    def add_entity(self, entity: LaunchDescriptionEntity) -> None:
        _check_entity(entity)
        self.__entities.append(entity)

    def add_action(self, action: Action) -> None:
        self.add_entity(action)

    def visit(self, context: LaunchContext) -> list[LaunchDescriptionEntity]:
        if self.__deprecated_reason is not None:
            try:
                path = context.locals.current_launch_file_path
            except AttributeError:
                path = '<unknown>'
            get_logger().warning(f'launch file [{path}] is deprecated: {self.__deprecated_reason}')
        return self.__entities

    def describe(self) -> str:
        return f'LaunchDescription({len(self.__entities)} entities)'

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return self.__entities

    def get_launch_arguments(self, conditional_inclusion: bool = False) -> list[DeclareLaunchArgument]:
        """Every DeclareLaunchArgument reachable without running, first of each name kept.

        With conditional_inclusion=True each argument gets `_conditionally_included` set to
        whether it is only reached under some condition.
        """
        # Lazy: launch.actions imports the frontend, whose parser imports this module (a cycle).
        from launch.actions.declare_launch_argument import DeclareLaunchArgument

        found: dict[str, DeclareLaunchArgument] = {}

        def walk(entities: Iterable[LaunchDescriptionEntity], conditional: bool) -> None:
            for entity in entities:
                if isinstance(entity, DeclareLaunchArgument):
                    if entity.name not in found:
                        entity._conditionally_included = (
                            conditional or entity.condition is not None)
                        found[entity.name] = entity
                    continue
                entity_conditional = conditional or getattr(entity, 'condition', None) is not None
                walk(entity.describe_sub_entities(), entity_conditional)
                for _description, sub_entities in entity.describe_conditional_sub_entities():
                    walk(sub_entities, True)

        walk(self.__entities, False)
        return list(found.values())


def _check_entity(entity: object) -> None:
    if not isinstance(entity, LaunchDescriptionEntity):
        raise TypeError(f"LaunchDescription expects launch entities (actions, descriptions), got "
                        f"'{type(entity).__name__}': {entity!r}")
