"""Substitutions: pieces of text computed lazily, when the action that owns them executes."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class Substitution:
    """Base class: perform(context) gives the text, describe() a readable form without a context."""

    def perform(self, context: LaunchContext) -> str:
        raise NotImplementedError(type(self).__name__)

    def describe(self) -> str:
        return type(self).__name__ + '(...)'


def describe_substitutions(subs: Iterable[Substitution]) -> str:
    return ' + '.join(sub.describe() for sub in subs)
