"""PythonExpression: the value of a Python expression."""

from __future__ import annotations

import importlib
import math
from collections.abc import Iterable
from typing import TYPE_CHECKING

from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution, describe_substitutions
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


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
