"""GroupAction: actions under one condition, by default in their own configuration scope."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.actions.pop_environment import PopEnvironment
from launch.actions.pop_launch_configurations import PopLaunchConfigurations
from launch.actions.push_environment import PushEnvironment
from launch.actions.push_launch_configurations import PushLaunchConfigurations
from launch.actions.reset_environment import ResetEnvironment
from launch.actions.reset_launch_configurations import ResetLaunchConfigurations
from launch.actions.set_launch_configuration import SetLaunchConfiguration
from launch.frontend.expose import expose_action
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('group')
class GroupAction(Action):
    """scoped (default): configurations and environment set inside do not leak out.

    forwarding=False additionally starts the group from the launch's initial environment and only
    the given launch_configurations.  The scope ends once the grouped actions have been visited.
    """

    def __init__(self, actions: Iterable[Action], *, scoped: bool = True, forwarding: bool = True,
                 launch_configurations: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
                 **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.actions = list(actions)
        self.scoped = scoped
        self.forwarding = forwarding
        self.launch_configurations = [
            (normalize_to_list_of_substitutions(k), normalize_to_list_of_substitutions(v))
            for k, v in (launch_configurations or {}).items()]

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        kwargs: dict[str, Any] = {}
        for flag in ('scoped', 'forwarding'):
            value = parser.boolean(entity, flag)
            if value is not None:
                kwargs[flag] = value
        keep = {}
        for item in entity.get_children('keep'):
            keep[tuple(parser.substitutions(item.get_attr('name')))] = parser.substitutions(
                item.get_attr('value'))
            item.assert_entity_completely_parsed()
        if keep:
            kwargs['launch_configurations'] = {key: value for key, value in keep.items()}
        kwargs['actions'] = parser.parse_actions(entity.action_children())
        return cls, kwargs

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return list(self.actions)

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """What executing the group runs: its actions inside the scope actions it needs."""
        kept = {tuple(k): v for k, v in self.launch_configurations}
        return self._scoped_actions(kept)

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity]:
        # Kept values are read before the group resets the environment they may depend on.
        return self._scoped_actions({perform_substitutions(context, k): perform_substitutions(context, v)
                                     for k, v in self.launch_configurations})

    def _scoped_actions(self, kept: dict[Any, Any]) -> list[LaunchDescriptionEntity]:
        settings = [SetLaunchConfiguration(k, v) for k, v in self.launch_configurations]
        if not self.scoped:
            return [*settings, *self.actions]
        if self.forwarding:
            return [PushLaunchConfigurations(), PushEnvironment(), *settings, *self.actions,
                    PopEnvironment(), PopLaunchConfigurations()]
        return [PushLaunchConfigurations(), PushEnvironment(), ResetEnvironment(),
                ResetLaunchConfigurations(kept), *self.actions,
                PopEnvironment(), PopLaunchConfigurations()]
