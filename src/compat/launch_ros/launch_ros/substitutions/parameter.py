"""Parameter (`$(param name)`): the value a SetParameter earlier in scope gave a parameter."""

from __future__ import annotations

from typing import TYPE_CHECKING

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
    the name was set more than once, the latest value counts, the one the nodes end up with.
    """

    def __init__(self, name: SomeSubstitutionsType) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def describe(self) -> str:
        """'Parameter(name=...)': a readable form without a context."""
        return f"Parameter(name={' + '.join(sub.describe() for sub in self.name)})"

    def perform(self, context: LaunchContext) -> str:
        """The latest value set for the name in scope; SubstitutionFailure if there is none."""
        name = perform_substitutions(context, self.name)
        for item in reversed(context.launch_configurations.get('global_params', [])):
            if isinstance(item, tuple) and item[0] == name:
                value = item[1]
                return value if isinstance(value, str) else yaml_text(value)
        raise SubstitutionFailure(f"parameter '{name}' not found: no SetParameter for it in this scope")


@expose_substitution('param', 1)
def _param(name: list) -> Parameter:
    return Parameter(name)
