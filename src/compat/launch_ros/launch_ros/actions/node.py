"""Node: ExecuteProcess for a ROS node, with the command line upstream launch_ros builds.

argv = [launch-prefix...] <prefix>/lib/<package>/<executable> <arguments...>
       [--ros-args <ros_arguments...>] --ros-args [-r __node:=<name>] [-r __ns:=<namespace>]
       <SetParameter / SetParametersFromFile in scope> <parameters, in order> <SetRemap rules> <remappings>
       <what 'launch_ros.node_action' extensions add>
"""

from __future__ import annotations

import os
import pathlib
import re
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.actions import ExecuteProcess
from launch.actions.execute_process import split_command_line
from launch.frontend.expose import expose_action, get_entry_points
from launch.logging import get_logger
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.parameter_descriptions import Parameter, ParameterFile, ParameterValue
from launch_ros.parameters import flatten_parameters, write_parameters_file, yaml_text
from launch_ros.substitutions import ExecutableInPackage
from launch_ros.utilities.namespace_utils import make_namespace_absolute, prefix_namespace
from launch_ros.utilities.normalize_parameters import check_parameters_item
from launch_ros.utilities.normalize_remap_rule import normalize_remap_rules
from launch_ros.utilities.plugin_support import PluginException, satisfies_version
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

    # Stand-ins in node_name for what was not given, so that node_name always has both parts.
    UNSPECIFIED_NODE_NAME = '<node_name_unspecified>'
    UNSPECIFIED_NODE_NAMESPACE = '<node_namespace_unspecified>'

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
        self.__package_as_given = package
        self.__executable_as_given = executable
        self.__package = None if package is None else normalize_to_list_of_substitutions(package)
        self.__executable = normalize_to_list_of_substitutions(executable)
        self.__node_name = None if name is None else normalize_to_list_of_substitutions(name)
        self.__node_namespace = None if namespace is None else normalize_to_list_of_substitutions(namespace)
        self.__parameters = list(parameters or [])
        self.__remappings = list(normalize_remap_rules(remappings or []))
        self.__executed = False
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

    @staticmethod
    def parse_nested_parameters(params: list[Entity], parser: Parser) -> list[Any]:
        """<param> entities as the items of Node(parameters=...): dicts of values, and parameter files."""
        return parse_parameter_entities(params, parser)

    # ---- names ----
    @property
    def node_package(self) -> SomeSubstitutionsType | None:
        """The package, as given to the constructor."""
        return self.__package_as_given

    @property
    def node_executable(self) -> SomeSubstitutionsType:
        """The executable, as given to the constructor."""
        return self.__executable_as_given

    @property
    def node_name(self) -> str:
        """The fully qualified node name; RuntimeError before the action is executed.

        A part that was not given (no name, no namespace given nor pushed) is UNSPECIFIED_NODE_NAME or
        UNSPECIFIED_NODE_NAMESPACE: the node then picks it itself.
        """
        if not self.__executed:
            raise RuntimeError("cannot access 'node_name' before executing action")
        name = prefix_namespace(self.expanded_node_namespace,
                                self.__expanded_name or self.UNSPECIFIED_NODE_NAME)
        assert name is not None  # both parts are text
        return name

    def is_node_name_fully_specified(self) -> bool:
        """Whether launch gave the node both its name and its namespace (so node_name is its real name)."""
        return self.UNSPECIFIED_NODE_NAME not in self.node_name and \
            self.UNSPECIFIED_NODE_NAMESPACE not in self.node_name

    @property
    def expanded_node_namespace(self) -> str:
        """The node's absolute namespace, pushed ones included; UNSPECIFIED_NODE_NAMESPACE until known."""
        return self.__expanded_namespace or self.UNSPECIFIED_NODE_NAMESPACE

    @property
    def expanded_remapping_rules(self) -> list[tuple[str, str]] | None:
        """The (from, to) remappings passed on the command line, scoped ones first; None if there are none."""
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
            if self.__node_namespace is not None:
                namespace = perform_substitutions(context, self.__node_namespace)
            namespace = make_namespace_absolute(
                prefix_namespace(context.launch_configurations.get('ros_namespace'), namespace))
            if namespace is not None:
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
        self.__executed = True

    def execute(self, context: LaunchContext) -> None:
        """Expand and check the node's name and namespace, then start the process.

        Warns when another node of this launch already has the same full name (both given).
        """
        self._expand_names(context)
        super().execute(context)
        label = self.process_description.final_name
        if self.is_node_name_fully_specified() and label is not None:
            add_node_name(context, self.node_name)
            count = get_node_name_count(context, self.node_name)
            if count > 1:
                get_logger(label).warning(
                    f'there are now at least {count} nodes with the name {self.node_name} created '
                    'within this launch context')

    def _extra_arguments(self, context: LaunchContext) -> list[str]:
        # The -r values for name and namespace, which extensions may change.
        ros_specific_arguments: dict[str, Any] = {'ns': f'__ns:={self.expanded_node_namespace}'}
        if self.__expanded_name is not None:
            ros_specific_arguments['name'] = f'__node:={self.__expanded_name}'
        extension_arguments: list[str] = []
        for extension in get_extensions(get_logger('launch_ros.actions.node')).values():
            added, ros_specific_arguments = extension.prepare_for_execute(
                context, ros_specific_arguments, self)
            extension_arguments += [perform_substitutions(context, normalize_to_list_of_substitutions(item))
                                    for item in added]
        context.extend_locals({'ros_specific_arguments': ros_specific_arguments})
        args = ['--ros-args']
        if self.__expanded_name is not None:
            args += ['-r', ros_specific_arguments['name']]
        if self.__expanded_namespace is not None:
            args += ['-r', ros_specific_arguments['ns']]
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
        self.__expanded_remappings = remappings or None
        for src, dst in remappings:
            args += ['-r', f'{src}:={dst}']
        return args + extension_arguments

    def _parameter_arguments(self, context: LaunchContext, parameter: Any) -> list[str]:
        if isinstance(parameter, dict):
            key = self.node_name if self.is_node_name_fully_specified() else '/**'
            return ['--params-file', write_parameters_file(key, flatten_parameters(context, parameter))]
        if isinstance(parameter, Parameter):
            name, value = parameter.evaluate(context)
            return ['-p', f'{name}:={yaml_text(value)}']
        if isinstance(parameter, ParameterFile):
            path = str(parameter.evaluate(context))
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


class NodeActionExtension:
    """Base of the plugins every Node consults before it starts (entry point group 'launch_ros.node_action').

    NAME becomes the entry point's name. A plugin written for another major version of this extension
    point (EXTENSION_POINT_VERSION) is refused when instantiated, with a PluginException.
    """

    NAME: str | None = None
    EXTENSION_POINT_VERSION = '0.1'

    def __init__(self) -> None:
        satisfies_version(self.EXTENSION_POINT_VERSION, '^0.1')

    def prepare_for_execute(self, context: LaunchContext, ros_specific_arguments: dict[str, Any],
                            node_action: Node) -> tuple[list[SomeSubstitutionsType], dict[str, Any]]:
        """Items to add at the end of the node's command line, and the ROS-specific arguments to use.

        ros_specific_arguments holds the values Node passes with -r: 'name' ('__node:=<name>', when
        the node has one) and 'ns' ('__ns:=<namespace>'). This base adds nothing and changes nothing.
        """
        return [], ros_specific_arguments


def instantiate_extension(group_name: str, extension_name: str, extension_class: type,
                          extensions: dict[str, Any], logger: Any, *, unique_instance: bool = False) -> Any:
    """An instance of extension_class, or None (logged) if it cannot be made.

    Unless unique_instance, an instance already in extensions under extension_name is reused and a new
    one is stored there.
    """
    if not unique_instance and extension_name in extensions:
        return extensions[extension_name]
    try:
        instance = extension_class()
    except PluginException as error:
        logger.warning(f"Failed to instantiate '{group_name}' extension '{extension_name}': {error}")
        return None
    except Exception as error:
        logger.error(f"Failed to instantiate '{group_name}' extension '{extension_name}': {error}")
        return None
    if not unique_instance:
        extensions[extension_name] = instance
    return instance


def get_extensions(logger: Any) -> dict[str, Any]:
    """The installed 'launch_ros.node_action' extensions, by entry point name, each a new instance.

    One that cannot be loaded or instantiated is left out, with a message on logger.
    """
    group = 'launch_ros.node_action'
    extensions: dict[str, Any] = {}
    for entry_point in get_entry_points(group):
        try:
            extension_class = entry_point.load()
        except Exception as error:
            logger.warning(f"Failed to load entry point '{entry_point.name}': {error}")
            continue
        instance = instantiate_extension(group, entry_point.name, extension_class, extensions, logger)
        if instance is not None:
            instance.NAME = entry_point.name
    return extensions


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
