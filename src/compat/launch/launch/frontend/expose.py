"""Registries of the frontend: which class a tag builds, which substitution a `$(name)` makes.

launch's own modules fill them when imported; other packages (launch_ros) extend them through the
entry point group 'launch.frontend.launch_extension', whose modules are imported before a launch
file or a `$(...)` value is first parsed.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol, TypeVar

if TYPE_CHECKING:
    from importlib.metadata import EntryPoint

    from launch.frontend.entity import Entity
    from launch.frontend.parser import Parser
    from launch.substitution import Substitution


class ParsesEntity(Protocol):
    """An action class a tag builds.

    Its parse classmethod reads the tag into the class to make and that class's constructor arguments
    (whose types only that class knows).
    """

    def parse(self, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]: ...


ActionClass = TypeVar('ActionClass', bound=ParsesEntity)
# One `$(name arg ...)`: each argument is the substitutions of its text.
SubstitutionArguments = list[list['Substitution']]

# tag -> class with parse(entity, parser) -> (class, constructor kwargs)
action_parse_methods: dict[str, ParsesEntity] = {}
# name -> function(list of argument substitution lists) -> Substitution
substitution_parse_methods: dict[str, Callable[[SubstitutionArguments], Substitution]] = {}


def expose_action(tag: str) -> Callable[[ActionClass], ActionClass]:
    """Class decorator: the frontend tag `tag` builds this action through its parse classmethod."""
    def register(cls: ActionClass) -> ActionClass:
        action_parse_methods[tag] = cls
        return cls
    return register


SubstitutionMaker = TypeVar('SubstitutionMaker', bound=Callable[..., 'Substitution'])


def expose_substitution(name: str, min_args: int = 0, max_args: int | None = None
                        ) -> Callable[[SubstitutionMaker], SubstitutionMaker]:
    """Function decorator: `$(name arg...)` calls it with the arguments' substitution lists."""
    def register(function: SubstitutionMaker) -> SubstitutionMaker:
        def checked(args: SubstitutionArguments) -> Substitution:
            upper = min_args if max_args is None else max_args
            if not min_args <= len(args) <= upper:
                expected = str(min_args) if upper == min_args else f'{min_args} to {upper}'
                raise ValueError(f"substitution '{name}' expects {expected} argument(s), got {len(args)}")
            return function(*args)
        substitution_parse_methods[name] = checked
        return function
    return register


# The installed entry points, read once: reading them scans every distribution (some 10 ms).
_installed_entry_points: Any = None
_extensions_loaded = False


def get_entry_points(group: str) -> list[EntryPoint]:
    """The installed entry points of one group, in the order importlib.metadata finds them."""
    global _installed_entry_points
    if _installed_entry_points is None:
        # Lazy: importing importlib.metadata takes some 20 ms, and only a parse needs it.
        from importlib.metadata import entry_points

        _installed_entry_points = entry_points()
    return list(_installed_entry_points.select(group=group))


def load_launch_extensions() -> None:
    """Import the modules of the 'launch.frontend.launch_extension' entry points, once.

    Importing them registers their actions and substitutions here (launch_ros's `<node>`,
    `$(find-pkg-share ...)`...).
    """
    global _extensions_loaded
    if _extensions_loaded:
        return
    for entry_point in get_entry_points('launch.frontend.launch_extension'):
        entry_point.load()
    _extensions_loaded = True
