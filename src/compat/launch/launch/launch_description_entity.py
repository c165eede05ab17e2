"""The base of everything a launch description holds."""

from __future__ import annotations

import asyncio
from collections.abc import Iterable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class LaunchDescriptionEntity:
    """Visited once at launch time; may yield sub-entities and a future that keeps launch busy."""

    def visit(self, context: LaunchContext) -> Iterable[LaunchDescriptionEntity] | None:
        return None

    def get_asyncio_future(self) -> asyncio.Future | None:
        return None

    def describe(self) -> str:
        return type(self).__name__

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return []

    def describe_conditional_sub_entities(
            self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        return []
