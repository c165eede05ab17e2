"""Actions that affect every Node executed after them in the same scope (group)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.substitution import (
    SomeSubstitutionsType,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

from launch_ros.actions.node import join_namespaces, make_namespace_absolute, validate_namespace
from launch_ros.parameters import evaluate_value

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
            join_namespaces(pushed, perform_substitutions(context, self.namespace)))
        validate_namespace(namespace)
        context.launch_configurations['ros_namespace'] = namespace


PushRosNamespace = PushROSNamespace


@expose_action('set_parameter')
class SetParameter(Action):
    """Every Node after this one (in scope) gets `-p name:=value`."""

    def __init__(self, name: SomeSubstitutionsType, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = value

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <set_parameter> tag's name and value (a non-text YAML value passes as it is)."""
        value = entity.get_attr('value')
        return cls, {'name': parser.substitutions(entity.get_attr('name')),
                     'value': parser.substitutions(value) if isinstance(value, str) else value}

    def execute(self, context: LaunchContext) -> None:
        """Add name:=value to the parameters the scope's later Nodes get."""
        name = perform_substitutions(context, self.name)
        value = evaluate_value(context, self.value, name)
        # A new list, not an append: the enclosing scope keeps its own.
        context.launch_configurations['global_params'] = [
            *context.launch_configurations.get('global_params', []), (name, value)]


@expose_action('set_parameters_from_file')
class SetParametersFromFile(Action):
    """Every Node after this one (in scope) gets `--params-file <filename>`."""

    def __init__(self, filename: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.filename = normalize_to_list_of_substitutions(filename)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <set_parameters_from_file> tag's filename attribute."""
        return cls, {'filename': parser.substitutions(entity.get_attr('filename'))}

    def execute(self, context: LaunchContext) -> None:
        """Add the file, as an absolute path, to the parameters the scope's later Nodes get."""
        path = os.path.abspath(perform_substitutions(context, self.filename))
        context.launch_configurations['global_params'] = [
            *context.launch_configurations.get('global_params', []), path]


@expose_action('set_remap')
class SetRemap(Action):
    """Every Node after this one (in scope) gets `-r src:=dst`, before its own remappings."""

    def __init__(self, src: SomeSubstitutionsType, dst: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.src = normalize_to_list_of_substitutions(src)
        self.dst = normalize_to_list_of_substitutions(dst)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <set_remap> tag's from and to attributes."""
        return cls, {'src': parser.substitutions(entity.get_attr('from')),
                     'dst': parser.substitutions(entity.get_attr('to'))}

    def execute(self, context: LaunchContext) -> None:
        """Add the rule to the remappings the scope's later Nodes get."""
        rule = (perform_substitutions(context, self.src), perform_substitutions(context, self.dst))
        context.launch_configurations['ros_remaps'] = [
            *context.launch_configurations.get('ros_remaps', []), rule]
