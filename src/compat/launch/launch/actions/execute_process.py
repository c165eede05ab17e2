"""ExecuteProcess: ExecuteLocal of a command line given as cmd, prefix, name, cwd and env."""

from __future__ import annotations

import re
import shlex
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.actions.execute_local import ExecuteLocal
from launch.actions.shutdown_action import Shutdown
from launch.descriptions.executable import Executable
from launch.frontend.expose import expose_action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution
from launch.substitutions.text_substitution import TextSubstitution

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser


@expose_action('executable')
class ExecuteProcess(ExecuteLocal):
    """Run cmd as a local process; the other keyword arguments are ExecuteLocal's."""

    def __init__(
            self, *, cmd: Iterable[SomeSubstitutionsType], prefix: SomeSubstitutionsType | None = None,
            name: SomeSubstitutionsType | None = None, cwd: SomeSubstitutionsType | None = None,
            env: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
            additional_env: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
            **kwargs: Any) -> None:
        description = Executable(cmd=cmd, prefix=prefix, name=name, cwd=cwd, env=env,
                                 additional_env=additional_env)
        super().__init__(process_description=description, **kwargs)

    @property
    def cmd(self) -> list[list[Substitution]]:
        return self.process_description.cmd

    @property
    def name(self) -> list[Substitution] | None:
        return self.process_description.name

    @property
    def cwd(self) -> list[Substitution] | None:
        return self.process_description.cwd

    @property
    def env(self) -> list[tuple[list[Substitution], list[Substitution]]] | None:
        return self.process_description.env

    @property
    def additional_env(self) -> list[tuple[list[Substitution], list[Substitution]]] | None:
        return self.process_description.additional_env

    @classmethod
    def _parse_process_attributes(cls, entity: Entity, parser: Parser) -> dict[str, Any]:
        """The attributes <executable> and <node> share."""
        kwargs: dict[str, Any] = {}
        for attribute, keyword in (('cwd', 'cwd'), ('name', 'name'), ('launch-prefix', 'prefix'),
                                   ('output', 'output'), ('respawn', 'respawn')):
            value = entity.get_attr(attribute, optional=True)
            if value is not None:
                kwargs[keyword] = parser.substitutions(value)
        # Typed as upstream types them; where the action performs it at run time, a `$(...)` too.
        for attribute, data_type, may_substitute in (
                ('shell', bool, False), ('emulate_tty', bool, True), ('sigterm_timeout', float, True),
                ('sigkill_timeout', float, True), ('respawn_delay', float, False),
                ('respawn_max_retries', int, False)):
            value = typed_attribute(entity, parser, attribute, data_type, may_substitute)
            if isinstance(value, float) and value < 0:
                raise entity.error(f"attribute '{attribute}' must not be negative, got {value}")
            if value is not None:
                kwargs[attribute] = value
        for timeout in ('sigterm_timeout', 'sigkill_timeout'):
            if isinstance(kwargs.get(timeout), float):
                kwargs[timeout] = str(kwargs[timeout])  # the constructor takes text or substitutions
        on_exit = entity.get_attr('on_exit', optional=True)
        if on_exit is not None:
            if on_exit != 'shutdown':
                raise entity.error(f"on_exit only supports 'shutdown', got {on_exit!r}")
            kwargs['on_exit'] = [Shutdown()]
        env = entity.get_children('env')
        if env:
            kwargs['additional_env'] = [(parser.substitutions(e.get_attr('name')),
                                         parser.substitutions(e.get_attr('value'))) for e in env]
            for e in env:
                e.assert_entity_completely_parsed()
        return kwargs

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        kwargs = cls._parse_process_attributes(entity, parser)
        kwargs['cmd'] = split_command_line(parser.substitutions(entity.get_attr('cmd')))
        return cls, kwargs


def typed_attribute(entity: Entity, parser: Parser, name: str, data_type: type,
                    may_substitute: bool = True) -> Any:
    """An optional attribute as a value of data_type, or (if allowed) substitutions for a `$(...)`."""
    value = parser.parse_if_substitutions(entity.get_attr(name, data_type=data_type, optional=True))
    if isinstance(value, list) and not may_substitute:
        raise entity.error(f"attribute '{name}' of `{entity.type_name}` must be a literal "
                           f'{data_type.__name__}, not a substitution')
    if isinstance(value, str) and data_type is not str:
        raise entity.error(f"attribute '{name}' of `{entity.type_name}` must be a {data_type.__name__}, "
                           f'got {value!r}')
    return value


def split_command_line(substitutions: list[Substitution]) -> list[list[Substitution]]:
    """Split a frontend `cmd` into argv items with shell quoting rules applied to its literal text.

    Substitutions (also inside quotes) stay where they are, each a placeholder while splitting, so
    a substitution glued to text is in the same item and its own value is never split.
    """
    placeholders: dict[str, Substitution] = {}
    text = []
    for sub in substitutions:
        if isinstance(sub, TextSubstitution):
            text.append(sub.text)
        else:
            marker = f'\0{len(placeholders)}\0'
            placeholders[marker] = sub
            text.append(marker)
    try:
        tokens = shlex.split(''.join(text))
    except ValueError as error:  # e.g. an unclosed quote
        raise ValueError(f"cannot split command line '{''.join(text)}': {error}") from None
    items = []
    for token in tokens:
        item: list[Substitution] = []
        for piece in re.split('(\0\\d+\0)', token):
            if piece in placeholders:
                item.append(placeholders[piece])
            elif piece:
                item.append(TextSubstitution(text=piece))
        items.append(item or [TextSubstitution(text='')])
    return items
