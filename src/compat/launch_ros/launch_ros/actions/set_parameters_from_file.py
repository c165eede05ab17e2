"""SetParametersFromFile: every Node after it (in scope) gets `--params-file <filename>`."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('set_parameters_from_file')
class SetParametersFromFile(Action):
    """Every Node after this one (in scope) gets `--params-file <filename>`."""

    def __init__(self, filename: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.filename = normalize_to_list_of_substitutions(filename)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <set_parameters_from_file> tag's filename attribute."""
        return cls, {'filename': parser.substitutions(entity.get_attr('filename'))}

    def execute(self, context: LaunchContext) -> None:
        """Add the file, as an absolute path, to the parameters the scope's later Nodes get."""
        path = os.path.abspath(perform_substitutions(context, self.filename))
        context.launch_configurations['global_params'] = [
            *context.launch_configurations.get('global_params', []), path]
