"""SomeActionsType: one action or several (upstream's name until Iron)."""

from __future__ import annotations

from collections.abc import Iterable

from launch.action import Action

SomeActionsType = Action | Iterable[Action]
SomeActionsType_types_tuple = (Action, Iterable)
