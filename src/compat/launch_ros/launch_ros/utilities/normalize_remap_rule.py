"""Remapping rules checked and normalised at construction."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from launch.utilities import normalize_to_list_of_substitutions

from launch_ros.remap_rule_type import RemapRule, SomeRemapRules

__all__ = ['normalize_remap_rule', 'normalize_remap_rules']


def normalize_remap_rule(remap_rule: Any) -> RemapRule:
    """A (from, to) remapping as two tuples of substitutions; TypeError for anything but a 2-tuple."""
    if not isinstance(remap_rule, tuple):
        raise TypeError(f"remap_rule must be a tuple of length 2 (from, to), got "
                        f"'{type(remap_rule).__name__}': {remap_rule!r}")
    if len(remap_rule) != 2:
        raise TypeError(f'remap_rule must be a tuple of length 2, got length {len(remap_rule)}')
    return (tuple(normalize_to_list_of_substitutions(remap_rule[0])),
            tuple(normalize_to_list_of_substitutions(remap_rule[1])))


def normalize_remap_rules(remap_rules: SomeRemapRules) -> Iterator[RemapRule]:
    """Each (from, to) remapping normalised, lazily and in order (as upstream, a generator)."""
    for rule in remap_rules:
        yield normalize_remap_rule(rule)
