"""IncludeLaunchDescription: run another launch file (or description) here, with arguments."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.launch_description_source import LaunchDescriptionSource
from launch.launch_description_sources.any_launch_description_source import AnyLaunchDescriptionSource
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


class _LaunchFileLocals(Action):
    """Enter (path given) or leave (None) the locals of an included launch file."""

    def __init__(self, path: str | None) -> None:
        super().__init__()
        self.path = path

    def execute(self, context: LaunchContext) -> None:
        if self.path is None:
            context._pop_locals()
            return
        context._push_locals()
        context.extend_locals({'current_launch_file_path': self.path,
                               'current_launch_file_directory': os.path.dirname(self.path)})


@expose_action('include')
class IncludeLaunchDescription(Action):
    """No scoping: arguments and configurations set inside stay set (wrap in a GroupAction)."""

    def __init__(self, launch_description_source: LaunchDescriptionSource | SomeSubstitutionsType, *,
                 launch_arguments: Iterable[tuple[SomeSubstitutionsType, SomeSubstitutionsType]]
                 | None = None,
                 **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if not isinstance(launch_description_source, LaunchDescriptionSource):
            launch_description_source = AnyLaunchDescriptionSource(launch_description_source)
        self.__source = launch_description_source
        self.__launch_arguments = [
            (normalize_to_list_of_substitutions(name), normalize_to_list_of_substitutions(value))
            for name, value in (launch_arguments or [])]

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        arguments = []
        for arg in entity.get_children('arg'):
            arguments.append((parser.substitutions(arg.get_attr('name')),
                              parser.substitutions(arg.get_attr('value'))))
            arg.assert_entity_completely_parsed()
        kwargs: dict[str, Any] = {
            'launch_description_source': parser.substitutions(entity.get_attr('file'))}
        if arguments:
            kwargs['launch_arguments'] = arguments
        return cls, kwargs

    @property
    def launch_description_source(self) -> LaunchDescriptionSource:
        return self.__source

    @property
    def launch_arguments(self) -> list[tuple[list, list]]:
        return self.__launch_arguments

    def describe(self) -> str:
        return f'IncludeLaunchDescription({self.__source.describe()})'

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        description = self.__source.try_get_launch_description_without_context()
        if description is None:
            return []
        # Arguments this include passes are not arguments of the including file.
        given = {''.join(getattr(s, 'text', '?') for s in name) for name, _ in self.__launch_arguments}
        return [entity for entity in description.get_launch_arguments() if entity.name not in given]

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """The included description, when it can be loaded without a launch context."""
        description = self.__source.try_get_launch_description_without_context()
        return [] if description is None else [description]

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity]:
        try:
            description = self.__source.get_launch_description(context)
        except Exception as error:
            location = self.__source._expanded_location
            if location and location not in str(error):  # e.g. a SyntaxError names the basename only
                raise RuntimeError(f'{error} (launch file: {os.path.abspath(location)})') from error
            raise
        location = self.__source.location
        path = os.path.abspath(location) if os.path.exists(location) else location
        given = []
        for name, value in self.__launch_arguments:
            name_text = perform_substitutions(context, name)
            context.launch_configurations[name_text] = perform_substitutions(context, value)
            given.append(name_text)
        for argument in description.get_launch_arguments(conditional_inclusion=True):
            if (argument.default_value is None and not argument._conditionally_included
                    and argument.name not in context.launch_configurations):
                raise RuntimeError(
                    f"Included launch description missing required argument '{argument.name}' "
                    f"(description: '{argument.description}'), given: [{', '.join(given)}] "
                    f'(launch file: {path})')
        return [_LaunchFileLocals(path), description, _LaunchFileLocals(None)]
