"""LocalSubstitution: a value from the context's locals."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.substitution import Substitution

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class LocalSubstitution(Substitution):
    """A value from context.locals, e.g. LocalSubstitution('event.reason') in an OnShutdown."""

    def __init__(self, expression: str, description: str | None = None) -> None:
        self.expression = expression
        self.description = description

    def perform(self, context: LaunchContext) -> str:
        return str(eval('context.locals.' + self.expression, {'context': context}))

    def describe(self) -> str:
        return self.description or f"LocalVar('{self.expression}')"
