"""The substitutions of launch: configurations, environment, paths, expressions, commands..."""

from __future__ import annotations

import importlib
import math
import os
import random
import shlex
import shutil
import socket
import subprocess
from collections.abc import Iterable
from typing import TYPE_CHECKING

from launch.conditions import InvalidConditionExpressionError, evaluate_condition_expression
from launch.logging import get_logger, launch_config
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution, describe_substitutions
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.substitutions.text_substitution import TextSubstitution
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = [
    'AllSubstitution', 'AndSubstitution', 'AnonName', 'AnySubstitution', 'Command',
    'EnvironmentVariable', 'EqualsSubstitution', 'FileContent', 'FindExecutable',
    'IfElseSubstitution', 'LaunchConfiguration', 'LaunchLogDir', 'LocalSubstitution',
    'NotEqualsSubstitution', 'NotSubstitution', 'OrSubstitution', 'PathJoinSubstitution',
    'PythonExpression', 'SubstitutionFailure', 'TextSubstitution', 'ThisLaunchFile',
    'ThisLaunchFileDir',
]


def _normalize_default(default: object) -> list[Substitution]:
    """Defaults may be plain values (sigterm_timeout defaults to 5): those become their str()."""
    if isinstance(default, (str, Substitution)):
        return normalize_to_list_of_substitutions(default)
    if isinstance(default, Iterable):
        return [item if isinstance(item, Substitution) else TextSubstitution(text=str(item))
                for item in default]
    return [TextSubstitution(text=str(default))]


class LaunchConfiguration(Substitution):
    """The value of a launch configuration (a declared argument, a `let`...)."""

    def __init__(self, variable_name: SomeSubstitutionsType, *, default: object = None) -> None:
        self.variable_name = normalize_to_list_of_substitutions(variable_name)
        self.default = None if default is None else _normalize_default(default)

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.variable_name)
        if name in context.launch_configurations:
            return context.launch_configurations[name]
        if self.default is None:
            raise SubstitutionFailure(f"launch configuration '{name}' does not exist")
        return perform_substitutions(context, self.default)

    def describe(self) -> str:
        return f'LaunchConfig({describe_substitutions(self.variable_name)})'


class EnvironmentVariable(Substitution):
    """The value of an environment variable of the launch process."""

    def __init__(self, name: SomeSubstitutionsType, *,
                 default_value: SomeSubstitutionsType | None = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.default_value = (None if default_value is None
                              else normalize_to_list_of_substitutions(default_value))

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        value = context.environment.get(name)
        if value is not None:
            return value
        if self.default_value is None:
            raise SubstitutionFailure(f"environment variable '{name}' does not exist")
        return perform_substitutions(context, self.default_value)

    def describe(self) -> str:
        return f'EnvVar({describe_substitutions(self.name)})'


class PathJoinSubstitution(Substitution):
    """os.path.join of the items; each item (str, substitution or list of them) is one component."""

    def __init__(self, substitutions: Iterable[SomeSubstitutionsType]) -> None:
        self.substitutions = [normalize_to_list_of_substitutions(item) for item in substitutions]

    def perform(self, context: LaunchContext) -> str:
        return os.path.join(*(perform_substitutions(context, item) for item in self.substitutions))

    def describe(self) -> str:
        return 'PathJoin(' + ', '.join(describe_substitutions(s) for s in self.substitutions) + ')'


class PythonExpression(Substitution):
    """str(eval(expression)); math's names are available unqualified, python_modules by name."""

    def __init__(self, expression: SomeSubstitutionsType,
                 python_modules: SomeSubstitutionsType | Iterable[SomeSubstitutionsType] = ('math',)
                 ) -> None:
        self.expression = normalize_to_list_of_substitutions(expression)
        if isinstance(python_modules, (str, Substitution)):
            python_modules = [python_modules]
        self.python_modules = [normalize_to_list_of_substitutions(m) for m in python_modules]

    def perform(self, context: LaunchContext) -> str:
        namespace: dict[str, object] = dict(vars(math))
        for module in self.python_modules:
            name = perform_substitutions(context, module)
            namespace[name.split('.')[0]] = importlib.import_module(name.split('.')[0])
            importlib.import_module(name)
        return str(eval(perform_substitutions(context, self.expression), namespace))

    def describe(self) -> str:
        return f'PythonExpr({describe_substitutions(self.expression)})'


class LocalSubstitution(Substitution):
    """A value from context.locals, e.g. LocalSubstitution('event.reason') in an OnShutdown."""

    def __init__(self, expression: str, description: str | None = None) -> None:
        self.expression = expression
        self.description = description

    def perform(self, context: LaunchContext) -> str:
        return str(eval('context.locals.' + self.expression, {'context': context}))

    def describe(self) -> str:
        return self.description or f"LocalVar('{self.expression}')"


class ThisLaunchFileDir(Substitution):
    """The directory of the launch file being loaded."""

    def perform(self, context: LaunchContext) -> str:
        try:
            return context.locals.current_launch_file_directory
        except AttributeError:
            raise SubstitutionFailure(
                'ThisLaunchFileDir used outside of a launch file (in a script)') from None

    def describe(self) -> str:
        return 'ThisLaunchFileDir()'


class ThisLaunchFile(Substitution):
    """The path of the launch file being loaded."""

    def perform(self, context: LaunchContext) -> str:
        try:
            return context.locals.current_launch_file_path
        except AttributeError:
            raise SubstitutionFailure(
                'ThisLaunchFile used outside of a launch file (in a script)') from None

    def describe(self) -> str:
        return 'ThisLaunchFile()'


class AnonName(Substitution):
    """<name>_<host>_<pid>_<random>, the same for the same name throughout one launch."""

    def __init__(self, name: SomeSubstitutionsType) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        key = 'anon' + name
        if key not in context.launch_configurations:
            raw = f'{name}_{socket.gethostname()}_{os.getpid()}_{random.randint(0, 2 ** 63)}'
            context.launch_configurations[key] = raw.replace('.', '_').replace('-', '_').replace(':', '_')
        return context.launch_configurations[key]

    def describe(self) -> str:
        return f'AnonName({describe_substitutions(self.name)})'


class FindExecutable(Substitution):
    """The full path of an executable on PATH."""

    def __init__(self, *, name: SomeSubstitutionsType) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        path = shutil.which(name, path=context.environment.get('PATH'))
        if path is None:
            raise SubstitutionFailure(f"executable '{name}' not found on the PATH")
        return path

    def describe(self) -> str:
        return f'FindExec({describe_substitutions(self.name)})'


class Command(Substitution):
    """The standard output of a command (split like a shell would, run without one)."""

    def __init__(self, command: SomeSubstitutionsType, *, on_stderr: SomeSubstitutionsType = 'fail') -> None:
        self.command = normalize_to_list_of_substitutions(command)
        self.on_stderr = normalize_to_list_of_substitutions(on_stderr)

    def perform(self, context: LaunchContext) -> str:
        command = perform_substitutions(context, self.command)
        on_stderr = perform_substitutions(context, self.on_stderr)
        if on_stderr not in ('fail', 'ignore', 'warn', 'capture'):
            raise SubstitutionFailure(f"expected 'on_stderr' to be one of: 'fail', 'ignore', 'warn' or "
                                      f"'capture', got '{on_stderr}'")
        try:
            argv = shlex.split(command)
        except ValueError as error:  # an unclosed quote
            raise SubstitutionFailure(f'cannot split command line: {command} ({error})') from None
        if not argv:
            raise SubstitutionFailure('the command of a Command substitution is empty')
        try:
            result = subprocess.run(
                argv, capture_output=True, text=True, errors='replace',
                env=dict(context.environment),
                stdin=subprocess.DEVNULL)
        except FileNotFoundError:
            raise SubstitutionFailure(f"file not found: '{argv[0]}' (command: {command})") from None
        except OSError as error:
            raise SubstitutionFailure(f'command could not run: {command} ({error.strerror})') from None
        if result.returncode != 0:
            message = f'executed command failed. Command: {command}'
            if result.stderr:
                message += f'\nCaptured stderr output: {result.stderr}'
            raise SubstitutionFailure(message)
        if result.stderr:
            if on_stderr == 'fail':
                raise SubstitutionFailure(f'executed command showed stderr output. Command: {command}\n'
                                          f'Captured stderr output:\n{result.stderr}')
            if on_stderr == 'warn':
                get_logger().warning(f'executed command showed stderr output. Command: {command}\n'
                                     f'Captured stderr output:\n{result.stderr}')
            if on_stderr == 'capture':
                return result.stdout + result.stderr
        return result.stdout

    def describe(self) -> str:
        return f'Command({describe_substitutions(self.command)})'


def _truth(context: LaunchContext, value: list[Substitution]) -> bool:
    """A boolean operand; one that is not true/false/1/0 is a SubstitutionFailure, as upstream."""
    try:
        return evaluate_condition_expression(context, value)
    except InvalidConditionExpressionError:
        text = perform_substitutions(context, value)
        raise SubstitutionFailure(f"'{text}' is not a valid boolean value, expected true, false, 1 or 0 "
                                  f"(expanded from {describe_substitutions(value)})") from None


class NotSubstitution(Substitution):
    def __init__(self, value: SomeSubstitutionsType) -> None:
        self.value = normalize_to_list_of_substitutions(value)

    def perform(self, context: LaunchContext) -> str:
        return str(not _truth(context, self.value)).lower()


class AndSubstitution(Substitution):
    def __init__(self, left: SomeSubstitutionsType, right: SomeSubstitutionsType) -> None:
        self.left = normalize_to_list_of_substitutions(left)
        self.right = normalize_to_list_of_substitutions(right)

    def perform(self, context: LaunchContext) -> str:
        return str(_truth(context, self.left) and _truth(context, self.right)).lower()


class OrSubstitution(AndSubstitution):
    def perform(self, context: LaunchContext) -> str:
        return str(_truth(context, self.left) or _truth(context, self.right)).lower()


class AnySubstitution(Substitution):
    def __init__(self, *args: SomeSubstitutionsType) -> None:
        self.args = [normalize_to_list_of_substitutions(arg) for arg in args]

    def perform(self, context: LaunchContext) -> str:
        return str(any(_truth(context, arg) for arg in self.args)).lower()


class AllSubstitution(AnySubstitution):
    def perform(self, context: LaunchContext) -> str:
        return str(all(_truth(context, arg) for arg in self.args)).lower()


def _comparable(value: object) -> list[Substitution]:
    """An EqualsSubstitution side: None is '', a bool is 'true'/'false', other values their str()."""
    from launch.utilities.type_utils import is_substitution

    if is_substitution(value):
        return normalize_to_list_of_substitutions(value)  # type: ignore[arg-type]
    if value is None:
        return [TextSubstitution(text='')]
    if isinstance(value, bool):
        return [TextSubstitution(text=str(value).lower())]
    return [TextSubstitution(text=str(value))]


def _is_boolean_text(text: str) -> bool:
    return text.lower() in ('true', 'false', '1', '0')


def _is_number_text(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


class EqualsSubstitution(Substitution):
    """'true' when both sides are equal, else 'false'.

    They are compared as booleans if both are true/false/1/0, as numbers (close enough) if both are
    numbers, else as text.  Sides may be any value: None, bools, numbers.
    """

    def __init__(self, left: object, right: object) -> None:
        self.left = _comparable(left)
        self.right = _comparable(right)

    def perform(self, context: LaunchContext) -> str:
        left = perform_substitutions(context, self.left)
        right = perform_substitutions(context, self.right)
        if _is_boolean_text(left) and _is_boolean_text(right):
            equal = (left.lower() in ('true', '1')) == (right.lower() in ('true', '1'))
        elif _is_number_text(left) and _is_number_text(right):
            equal = math.isclose(float(left), float(right))
        else:
            equal = left == right
        return str(equal).lower()

    def describe(self) -> str:
        left, right = describe_substitutions(self.left), describe_substitutions(self.right)
        return f'EqualsSubstitution({left}, {right})'


class NotEqualsSubstitution(EqualsSubstitution):
    def perform(self, context: LaunchContext) -> str:
        return str(super().perform(context) == 'false').lower()


class IfElseSubstitution(Substitution):
    def __init__(self, condition: SomeSubstitutionsType, if_value: SomeSubstitutionsType = '',
                 else_value: SomeSubstitutionsType = '') -> None:
        self.condition = normalize_to_list_of_substitutions(condition)
        self.if_value = normalize_to_list_of_substitutions(if_value)
        self.else_value = normalize_to_list_of_substitutions(else_value)

    def perform(self, context: LaunchContext) -> str:
        chosen = self.if_value if _truth(context, self.condition) else self.else_value
        return perform_substitutions(context, chosen)


class FileContent(Substitution):
    def __init__(self, path: SomeSubstitutionsType) -> None:
        self.path = normalize_to_list_of_substitutions(path)

    def perform(self, context: LaunchContext) -> str:
        path = perform_substitutions(context, self.path)
        try:
            with open(path, encoding='utf-8') as handle:
                return handle.read()
        except OSError as error:
            raise SubstitutionFailure(f"file '{path}' could not be read: {error.strerror}") from None


class LaunchLogDir(Substitution):
    """The directory this launch writes its logs to."""

    def perform(self, context: LaunchContext) -> str:
        if launch_config.log_dir is None:
            raise SubstitutionFailure('this launch has no log directory')
        return str(launch_config.log_dir)
