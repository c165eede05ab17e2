"""Remapping rules checked and normalised at construction."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from launch.substitution import Substitution
from launch.utilities import normalize_to_list_of_substitutions

__all__ = ['normalize_remap_rule', 'normalize_remap_rules']


def normalize_remap_rule(remap_rule: Any) -> tuple[list[Substitution], list[Substitution]]:
    """A (from, to) remapping as two substitution lists; TypeError for anything but a 2-tuple."""
    if not isinstance(remap_rule, tuple) or len(remap_rule) != 2:
        raise TypeError(f'remap_rule must be a tuple of length 2, got {remap_rule!r}')
    return (normalize_to_list_of_substitutions(remap_rule[0]),
            normalize_to_list_of_substitutions(remap_rule[1]))


def normalize_remap_rules(remap_rules: Iterable[Any]) -> list[tuple[list[Substitution], list[Substitution]]]:
    """Every (from, to) remapping of Node(remappings=...) normalised, in order."""
    return [normalize_remap_rule(rule) for rule in remap_rules]
