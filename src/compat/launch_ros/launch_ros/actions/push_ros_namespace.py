"""PushROSNamespace (humble: PushRosNamespace): a namespace for every Node after it in scope."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.actions.node import validate_namespace
from launch_ros.utilities.namespace_utils import make_namespace_absolute, prefix_namespace

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('push_ros_namespace')
@expose_action('push-ros-namespace')
class PushROSNamespace(Action):
    """Nodes after this one (in scope) get this namespace, or this namespace under theirs."""

    def __init__(self, namespace: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.namespace = normalize_to_list_of_substitutions(namespace)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <push_ros_namespace> tag's namespace attribute."""
        return cls, {'namespace': parser.substitutions(entity.get_attr('namespace'))}

    def execute(self, context: LaunchContext) -> None:
        """Push the namespace, under the one already pushed if relative; ValueError if it is not valid."""
        pushed = context.launch_configurations.get('ros_namespace')
        namespace = make_namespace_absolute(
            prefix_namespace(pushed, perform_substitutions(context, self.namespace)))
        validate_namespace(namespace)
        context.launch_configurations['ros_namespace'] = namespace


PushRosNamespace = PushROSNamespace
