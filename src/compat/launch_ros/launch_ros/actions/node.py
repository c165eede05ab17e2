"""Node: ExecuteProcess for a ROS node, with the command line upstream launch_ros builds.

argv = [launch-prefix...] <prefix>/lib/<package>/<executable> <arguments...>
       [--ros-args <ros_arguments...>] --ros-args [-r __node:=<name>] [-r __ns:=<namespace>]
       <SetParameter / SetParametersFromFile in scope> <parameters, in order> <SetRemap rules> <remappings>
"""

from __future__ import annotations

import os
import pathlib
import re
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.actions import ExecuteProcess
from launch.actions.execute_process import split_command_line
from launch.frontend.expose import expose_action
from launch.logging import get_logger
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.parameter_descriptions import Parameter, ParameterFile, ParameterValue
from launch_ros.parameters import flatten_parameters, write_parameters_file, yaml_text
from launch_ros.substitutions import ExecutableInPackage
from launch_ros.utilities.namespace_utils import join_namespaces, make_namespace_absolute
from launch_ros.utilities.normalize_parameters import check_parameters_item
from launch_ros.utilities.normalize_remap_rule import normalize_remap_rules
from launch_ros.utilities.track_node_names import add_node_name, get_node_name_count

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext

_NODE_NAME = re.compile(r'[A-Za-z_][A-Za-z0-9_]*\Z')
_NAMESPACE_TOKEN = re.compile(r'[A-Za-z_][A-Za-z0-9_]*\Z')
MAX_NAME_LENGTH = 255


def validate_node_name(name: str) -> None:
    """Rmw's rules: non-empty, letters, digits and _, not starting with a digit, at most 255."""
    if not name:
        raise ValueError('node name must not be empty')
    if len(name) > MAX_NAME_LENGTH:
        raise ValueError(f"node name '{name}' is longer than {MAX_NAME_LENGTH} characters")
    if not _NODE_NAME.match(name):
        raise ValueError(f"Invalid node name '{name}': node names must only contain alphanumeric "
                         "characters and underscores, and must not start with a number")


def validate_namespace(namespace: str) -> None:
    """Absolute, '/'-separated tokens of letters, digits and _, none starting with a digit."""
    if namespace == '/':
        return
    tokens = namespace.split('/')
    if not namespace.startswith('/') or namespace.endswith('/') or not all(
            _NAMESPACE_TOKEN.match(token) for token in tokens[1:]):
        raise ValueError(f"Invalid namespace '{namespace}': namespaces must be absolute, may only "
                         'contain alphanumeric characters, underscores and /, and no token may '
                         'start with a number')
    if len(namespace) > MAX_NAME_LENGTH:
        raise ValueError(f"namespace '{namespace}' is longer than {MAX_NAME_LENGTH} characters")


def _describe(substitutions: Iterable[Substitution]) -> str:
    """Substitutions as launch describes them: each one's describe(), joined by ' + '."""
    return ' + '.join(sub.describe() for sub in substitutions)


@expose_action('node')
class Node(ExecuteProcess):
    """A ROS node from a package (or an executable path when package is None)."""

    def __init__(self, *, executable: SomeSubstitutionsType, package: SomeSubstitutionsType | None = None,
                 name: SomeSubstitutionsType | None = None, namespace: SomeSubstitutionsType | None = None,
                 exec_name: SomeSubstitutionsType | None = None,
                 parameters: list[Any] | None = None,
                 remappings: Iterable[tuple[SomeSubstitutionsType, SomeSubstitutionsType]] | None = None,
                 ros_arguments: Iterable[SomeSubstitutionsType] | None = None,
                 arguments: Iterable[SomeSubstitutionsType] | None = None, **kwargs: Any) -> None:
        if 'cmd' in kwargs:
            raise TypeError("Node does not take 'cmd': use executable, arguments and ros_arguments")
        program: SomeSubstitutionsType = (executable if package is None
                                          else ExecutableInPackage(executable=executable, package=package))
        cmd: list[SomeSubstitutionsType] = [program, *(arguments or [])]
        if ros_arguments is not None:
            cmd += ['--ros-args', *ros_arguments]
        kwargs['name'] = exec_name
        super().__init__(cmd=cmd, **kwargs)
        if parameters is not None and not isinstance(parameters, list):
            raise TypeError(f"Node 'parameters' must be a list, got '{type(parameters).__name__}'")
        for parameter in parameters or []:
            check_parameters_item(parameter)
        self.__package = None if package is None else normalize_to_list_of_substitutions(package)
        self.__executable = normalize_to_list_of_substitutions(executable)
        self.__node_name = None if name is None else normalize_to_list_of_substitutions(name)
        self.__node_namespace = None if namespace is None else normalize_to_list_of_substitutions(namespace)
        self.__parameters = list(parameters or [])
        self.__remappings = normalize_remap_rules(remappings or [])
        self.__expanded_name: str | None = None
        self.__expanded_namespace: str | None = None
        self.__expanded_remappings: list[tuple[str, str]] | None = None

    # ---- frontend ----
    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <node> tag: process attributes, pkg, exec, name, namespace, args, <param>, <remap>."""
        kwargs = cls._parse_process_attributes(entity, parser)
        kwargs.pop('name', None)  # in <node>, name is the node name, not the process label
        kwargs['executable'] = parser.substitutions(entity.get_attr('exec'))
        for attribute, keyword in (('pkg', 'package'), ('name', 'name'), ('namespace', 'namespace'),
                                   ('exec_name', 'exec_name')):
            value = entity.get_attr(attribute, optional=True)
            if value is not None:
                kwargs[keyword] = parser.substitutions(value)
        for attribute, keyword in (('args', 'arguments'), ('ros_args', 'ros_arguments')):
            value = entity.get_attr(attribute, optional=True)
            if value is not None:
                kwargs[keyword] = split_command_line(parser.substitutions(value))
        parameters = parse_parameter_entities(entity.get_children('param'), parser)
        if parameters:
            kwargs['parameters'] = parameters
        remaps = []
        for remap in entity.get_children('remap'):
            remaps.append((parser.substitutions(remap.get_attr('from')),
                           parser.substitutions(remap.get_attr('to'))))
            remap.assert_entity_completely_parsed()
        if remaps:
            kwargs['remappings'] = remaps
        return cls, kwargs

    # ---- names ----
    @property
    def node_name(self) -> str:
        """The fully qualified node name once executed ('<unknown>' where the node picks its own)."""
        namespace = self.__expanded_namespace or '/'
        name = self.__expanded_name or '<unknown>'
        return namespace.rstrip('/') + '/' + name

    @property
    def expanded_node_namespace(self) -> str | None:
        """The node's absolute namespace, pushed ones included; None before execute or when none was given."""
        return self.__expanded_namespace

    @property
    def expanded_remapping_rules(self) -> list[tuple[str, str]] | None:
        """The (from, to) remappings passed on the command line, scoped ones first; None until then."""
        return self.__expanded_remappings

    def describe(self) -> str:
        """'Node(package=..., executable=...)': its line in LaunchIntrospector's tree."""
        package = _describe(self.__package) if self.__package else None
        return f'Node(package={package}, executable={_describe(self.__executable)})'

    def _expand_names(self, context: LaunchContext) -> None:
        name = namespace = None
        try:
            if self.__node_name is not None:
                name = perform_substitutions(context, self.__node_name)
                validate_node_name(name)
            pushed = context.launch_configurations.get('ros_namespace')
            if self.__node_namespace is not None:
                namespace = join_namespaces(pushed, perform_substitutions(context, self.__node_namespace))
            elif pushed:
                namespace = pushed
            if namespace is not None:
                namespace = make_namespace_absolute(namespace)
                validate_namespace(namespace)
        except Exception:
            describe = lambda subs: _describe(subs) if subs else None  # noqa: E731
            get_logger().error(
                'Error while expanding or validating node name or namespace for '
                f"'package={describe(self.__package)}, executable={describe(self.__executable)}, "
                f"name={describe(self.__node_name)}, namespace={describe(self.__node_namespace)}':")
            raise
        self.__expanded_name = name
        self.__expanded_namespace = namespace

    def execute(self, context: LaunchContext) -> None:
        """Expand and check the node's name and namespace, then start the process.

        Warns when another node of this launch already has the same full name.
        """
        self._expand_names(context)
        super().execute(context)
        label = self.process_description.final_name
        if self.__expanded_name is not None and label is not None:
            add_node_name(context, self.node_name)
            count = get_node_name_count(context, self.node_name)
            if count > 1:
                get_logger(label).warning(
                    f'there are now at least {count} nodes with the name {self.node_name} created '
                    'within this launch context')

    def _extra_arguments(self, context: LaunchContext) -> list[str]:
        args = ['--ros-args']
        if self.__expanded_name is not None:
            args += ['-r', f'__node:={self.__expanded_name}']
        if self.__expanded_namespace is not None:
            args += ['-r', f'__ns:={self.__expanded_namespace}']
        for item in context.launch_configurations.get('global_params', []):
            if isinstance(item, tuple):
                args += ['-p', f'{item[0]}:={item[1]}']
            else:
                args += ['--params-file', item]
        for parameter in self.__parameters:
            args += self._parameter_arguments(context, parameter)
        remappings = [(src, dst) for src, dst in context.launch_configurations.get('ros_remaps', [])]
        remappings += [(perform_substitutions(context, src), perform_substitutions(context, dst))
                       for src, dst in self.__remappings]
        self.__expanded_remappings = remappings
        for src, dst in remappings:
            args += ['-r', f'{src}:={dst}']
        return args

    def _parameter_arguments(self, context: LaunchContext, parameter: Any) -> list[str]:
        if isinstance(parameter, dict):
            known = self.__expanded_name is not None and self.__expanded_namespace is not None
            key = self.node_name if known else '/**'
            return ['--params-file', write_parameters_file(key, flatten_parameters(context, parameter))]
        if isinstance(parameter, Parameter):
            name, value = parameter.evaluate(context)
            return ['-p', f'{name}:={yaml_text(value)}']
        if isinstance(parameter, ParameterFile):
            path = parameter.evaluate(context)
        elif isinstance(parameter, (str, Substitution, pathlib.Path, list, tuple)):
            path = perform_substitutions(context, normalize_to_list_of_substitutions(
                str(parameter) if isinstance(parameter, pathlib.Path) else parameter))
        else:
            raise TypeError(f"Node parameters must be dicts, parameter files or Parameter objects, got "
                            f"'{type(parameter).__name__}'")
        if not os.path.isfile(path):
            get_logger('launch_ros.actions.node').warning(f'Parameter file path is not a file: {path}')
            return []
        return ['--params-file', path]


PARAMETER_TYPES = {
    'str': str, 'int': int, 'float': float, 'bool': bool, 'list_of_str': list[str],
    'list_of_int': list[int], 'list_of_float': list[float], 'list_of_bool': list[bool],
}


def parse_parameter_entities(entities: list[Entity], parser: Parser) -> list[Any]:
    """<param> children: name+value, name+nested params, or from=<file> (in document order)."""
    result: list[Any] = []
    values: dict[str, Any] = {}
    for entity in entities:
        source = entity.get_attr('from', optional=True)
        if source is not None:
            if values:
                result.append(values)
                values = {}
            allow = parser.boolean(entity, 'allow_substs')
            result.append(ParameterFile(parser.substitutions(source), allow_substs=bool(allow)))
            entity.assert_entity_completely_parsed()
            continue
        name = str(entity.get_attr('name'))
        nested = entity.get_children('param')
        if nested:
            for item in parse_parameter_entities(nested, parser):
                if not isinstance(item, dict):
                    raise entity.error('a parameter file cannot be nested inside a named <param>')
                values.setdefault(name, {}).update(item)
        else:
            values[name] = _parameter_value(entity, parser)
        entity.assert_entity_completely_parsed()
    if values:
        result.append(values)
    return result


def _parameter_value(entity: Entity, parser: Parser) -> Any:
    value = entity.get_attr('value')
    type_name = entity.get_attr('type', optional=True)
    separator = entity.get_attr('value-sep', optional=True)
    if isinstance(value, list):
        items: Any = [parser.substitutions(v) if isinstance(v, str) else v for v in value]
    elif separator is not None and isinstance(value, str):
        items = [parser.substitutions(v) for v in value.split(separator)]
    elif isinstance(value, str):
        items = parser.substitutions(value)
    else:
        items = value
    if type_name is None:
        return items
    if type_name == 'yaml':
        return items
    if type_name not in PARAMETER_TYPES:
        raise entity.error(f"unknown parameter type '{type_name}', expected one of "
                           f"{[*PARAMETER_TYPES, 'yaml']}")
    return ParameterValue(items, value_type=PARAMETER_TYPES[type_name])
