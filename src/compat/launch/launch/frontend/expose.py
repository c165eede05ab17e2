"""Registries of the frontend: which class a tag builds, which substitution a `$(name)` makes.

launch's own modules fill them when imported; other packages (launch_ros) extend them through the
entry point group 'launch.frontend.launch_extension', whose modules are imported before a launch
file or a `$(...)` value is first parsed.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:
    from importlib.metadata import EntryPoint

    from launch.frontend.entity import Entity
    from launch.frontend.parser import Parser
    from launch.substitution import Substitution


# What a tag's parse method gives: the action class to make and its constructor kwargs.
ParseResult = tuple[type, dict[str, Any]]
ParseAction = Callable[['Entity', 'Parser'], ParseResult]
ExposedAction = TypeVar('ExposedAction', bound=Callable[..., Any])
# One `$(name arg ...)`: each argument is the substitutions of its text.
SubstitutionArguments = list[list['Substitution']]

# tag -> parse(entity, parser) -> (action class, constructor kwargs)
action_parse_methods: dict[str, ParseAction] = {}
# name -> function(list of argument substitution lists) -> Substitution
substitution_parse_methods: dict[str, Callable[[SubstitutionArguments], Substitution]] = {}


def expose_action(tag: str) -> Callable[[ExposedAction], ExposedAction]:
    """Decorator: the frontend tag `tag` builds an action through what it decorates.

    A class with a `parse(entity, parser)` classmethod, or such a function, returning
    `(action class, constructor kwargs)`.
    """
    def register(exposed: ExposedAction) -> ExposedAction:
        action_parse_methods[tag] = _parse_method(f"expose_action('{tag}')", exposed)
        return exposed
    return register


def _parse_method(what: str, exposed: Any) -> Callable[..., Any]:
    """The parse classmethod of an exposed class, or the exposed function itself."""
    if isinstance(exposed, type):
        parse = getattr(exposed, 'parse', None)
        if not inspect.ismethod(parse):
            raise RuntimeError(f"{what}: class {exposed.__name__} has no 'parse' classmethod")
        return parse
    if inspect.isfunction(exposed):
        return exposed
    raise RuntimeError(f"{what}: expected a class with a 'parse' classmethod or a function, "
                       f'got {exposed!r}')


Exposed = TypeVar('Exposed', bound=Callable[..., Any])


def expose_substitution(name: str, min_args: int | None = None, max_args: int | None = None
                        ) -> Callable[[Exposed], Exposed]:
    """Decorator: `$(name arg...)` in a launch file makes a substitution through what it decorates.

    Upstream's contract, for third-party packages: a class with a `parse(data)` classmethod, or a
    function `parse(data)`, where data is the list of the arguments (each a list of
    substitutions) and the result is `(substitution class, constructor kwargs)`.

    With min_args (and max_args, default min_args), launch's own shorter form: the function is
    called with the arguments as positional parameters and returns the substitution itself.
    """
    def register(exposed: Exposed) -> Exposed:
        if min_args is not None:
            substitution_parse_methods[name] = _counted_maker(name, exposed, min_args, max_args)
            return exposed
        parse = _parse_method(f"expose_substitution('{name}')", exposed)
        substitution_parse_methods[name] = _from_parse_method(name, parse)
        return exposed
    return register


def _counted_maker(name: str, make: Callable[..., Substitution], min_args: int, max_args: int | None
                   ) -> Callable[[SubstitutionArguments], Substitution]:
    upper = min_args if max_args is None else max_args

    def checked(args: SubstitutionArguments) -> Substitution:
        if not min_args <= len(args) <= upper:
            expected = str(min_args) if upper == min_args else f'{min_args} to {upper}'
            raise ValueError(f"substitution '{name}' expects {expected} argument(s), got {len(args)}")
        return make(*args)
    return checked


def _from_parse_method(name: str, parse: Callable[[SubstitutionArguments], Any]
                       ) -> Callable[[SubstitutionArguments], Substitution]:
    def instantiate(args: SubstitutionArguments) -> Substitution:
        result = parse(args)
        if not (isinstance(result, tuple) and len(result) == 2 and isinstance(result[1], dict)):
            raise TypeError(f"the parse method of substitution '{name}' must return "
                            f'(class, kwargs), got {result!r}')
        substitution_class, kwargs = result
        return substitution_class(**kwargs)
    return instantiate


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
