"""Command: the standard output of a command."""

from __future__ import annotations

import shlex
import subprocess
from typing import TYPE_CHECKING

from launch.logging import get_logger
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution, describe_substitutions
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


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
