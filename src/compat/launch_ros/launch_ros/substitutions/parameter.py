"""Parameter (`$(param name [default])`): the value a SetParameter earlier in scope gave a parameter."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.frontend.expose import expose_substitution
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution
from launch.substitutions import SubstitutionFailure
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.parameters import yaml_text

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class Parameter(Substitution):
    """The value SetParameter(name, ...) set, as text (YAML for non-strings: true, 5, [1, 2]).

    Looks only at SetParameter (and SetUseSimTime), not at a Node's own parameters or files.  If
    the name was set more than once, the latest value counts, the one the nodes end up with.  When
    it was not set, the default is the text given instead; with no default that is a failure.
    """

    def __init__(self, name: SomeSubstitutionsType, *, default: Any = None) -> None:
        self.__name = normalize_to_list_of_substitutions(name)
        self.__default = None if default is None else _default_substitutions(default)

    @property
    def name(self) -> list[Substitution]:
        """The parameter's name, as substitutions."""
        return self.__name

    def describe(self) -> str:
        """'Parameter(name=...)': a readable form without a context."""
        return f"Parameter(name={' + '.join(sub.describe() for sub in self.name)})"

    def perform(self, context: LaunchContext) -> str:
        """The latest value set for the name in scope, else the default; SubstitutionFailure if neither."""
        name = perform_substitutions(context, self.name)
        for item in reversed(context.launch_configurations.get('global_params', [])):
            if isinstance(item, tuple) and item[0] == name:
                value = item[1]
                return value if isinstance(value, str) else yaml_text(value)
        if self.__default is None:
            raise SubstitutionFailure(f"parameter '{name}' not found: no SetParameter for it in this scope")
        return perform_substitutions(context, self.__default)


def _default_substitutions(default: Any) -> list[Substitution]:
    """The default as one text, as upstream makes it.

    Text and substitutions are kept, other values (5, True) become what str() gives, and the items of
    a list are put side by side.
    """
    items = default if isinstance(default, Iterable) and not isinstance(default, str) else [default]
    return normalize_to_list_of_substitutions(
        [item if isinstance(item, (str, Substitution)) else str(item) for item in items])


@expose_substitution('param', 1, 2)
def _param(name: list[Substitution], default: list[Substitution] | None = None) -> Parameter:
    return Parameter(name, default=default)
