"""Executable: what a process action runs, as substitutions until prepared in a launch context."""

from __future__ import annotations

import itertools
import os
import re
import shlex
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.action import Action
    from launch.launch_context import LaunchContext

# Every prepared executable gets the next number: labels are <name>-1, <name>-2, ...
_process_numbers = itertools.count(1)

SubstitutionPairs = list[tuple[list[Substitution], list[Substitution]]]


def _pairs(mapping: Any) -> SubstitutionPairs:
    """A dict (or pairs) of names and values, both as substitutions."""
    items = mapping.items() if isinstance(mapping, dict) else mapping
    return [(normalize_to_list_of_substitutions(key), normalize_to_list_of_substitutions(value))
            for key, value in items]


class Executable:
    """A command line with its label, directory and environment; final_* are set by prepare().

    Without a prefix, the launch configurations 'launch-prefix' (and 'launch-prefix-filter', a
    regular expression the program's basename must match) give it.  env replaces the launch's
    environment; additional_env is added to either.
    """

    def __init__(self, *, cmd: Iterable[SomeSubstitutionsType], prefix: SomeSubstitutionsType | None = None,
                 name: SomeSubstitutionsType | None = None, cwd: SomeSubstitutionsType | None = None,
                 env: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
                 additional_env: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
                 arguments: Iterable[SomeSubstitutionsType] | None = None) -> None:
        if isinstance(cmd, (str, Substitution)):
            raise TypeError("Executable 'cmd' must be a list of arguments (the program first), "
                            f'got {cmd!r}')
        self.__arguments = None if arguments is None else list(arguments)
        self.__cmd = [normalize_to_list_of_substitutions(item)
                      for item in [*cmd, *(self.__arguments or [])]]
        if not self.__cmd:
            raise ValueError("Executable 'cmd' is empty: it needs at least the program to run")
        self.__prefix = None if prefix is None else normalize_to_list_of_substitutions(prefix)
        self.__name = None if name is None else normalize_to_list_of_substitutions(name)
        self.__cwd = None if cwd is None else normalize_to_list_of_substitutions(cwd)
        self.__env = None if env is None else _pairs(env)
        self.__additional_env = None if additional_env is None else _pairs(additional_env)
        self.final_cmd: list[str] | None = None
        self.final_name: str | None = None
        self.final_cwd: str | None = None
        self.final_env: dict[str, str] | None = None

    @property
    def cmd(self) -> list[list[Substitution]]:
        """The program and its arguments (arguments included), each as substitutions."""
        return self.__cmd

    @property
    def prefix(self) -> list[Substitution] | None:
        return self.__prefix

    @property
    def name(self) -> list[Substitution] | None:
        return self.__name

    @property
    def cwd(self) -> list[Substitution] | None:
        return self.__cwd

    @property
    def env(self) -> SubstitutionPairs | None:
        return self.__env

    @property
    def additional_env(self) -> SubstitutionPairs | None:
        return self.__additional_env

    @property
    def arguments(self) -> list[SomeSubstitutionsType] | None:
        return self.__arguments

    def prepare(self, context: LaunchContext, action: Action) -> None:
        """Perform the substitutions and set final_cmd, final_name, final_cwd and final_env.

        action is the one that runs this executable; subclasses may read it.
        """
        cmd = [perform_substitutions(context, item) for item in self.__cmd]
        if self.__prefix is not None:
            prefix = perform_substitutions(context, self.__prefix)
        else:
            prefix = str(context.launch_configurations.get('launch-prefix', ''))
            prefix_filter = str(context.launch_configurations.get('launch-prefix-filter', ''))
            if prefix_filter and not re.match(prefix_filter, os.path.basename(cmd[0])):
                prefix = ''
        self.final_cmd = shlex.split(prefix) + cmd
        name = (perform_substitutions(context, self.__name) if self.__name is not None
                else os.path.basename(self.final_cmd[0]))
        self.final_name = f'{name}-{next(_process_numbers)}'
        self.final_cwd = None if self.__cwd is None else perform_substitutions(context, self.__cwd)
        if self.__env is not None:
            env = {perform_substitutions(context, k): perform_substitutions(context, v)
                   for k, v in self.__env}
        else:
            env = dict(context.environment)
        for key, value in self.__additional_env or []:
            env[perform_substitutions(context, key)] = perform_substitutions(context, value)
        self.final_env = env
