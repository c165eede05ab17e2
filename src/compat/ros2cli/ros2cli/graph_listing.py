"""What the list, type and find verbs of `ros2 topic`, `service` and `action` share.

Entries are the graph's [name, [type, ...]] pairs, sorted by name as rmw returns them.
"""

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

from ros2cli.node.graph import Graph

if TYPE_CHECKING:  # only for an annotation
    from ros2cli.node.strategy import NodeStrategy

Entries = Sequence[Sequence[Any]]


def types_of(entries: Entries, name: str) -> list[str] | None:
    """The types of the entry called name, or None when there is no such entry."""
    return next((list(types) for entry, types in entries if entry == name), None)


def print_listing(entries: Entries, show_types: bool, count_only: bool) -> int:
    """`list`: one name a line (with `[types]` for -t), or only how many there are (-c)."""
    if count_only:
        print(len(entries))
        return 0
    for name, types in entries:
        print(f"{name} [{', '.join(types)}]" if show_types else name)
    return 0


def print_names_of_type(entries: Entries, type_name: str, count_only: bool) -> int:
    """`find`: the names whose types include type_name, or only how many (-c)."""
    names = [name for name, types in entries if type_name in types]
    if count_only:
        print(len(names))
        return 0
    for name in names:
        print(name)
    return 0


def print_types(strategy: 'NodeStrategy', entries_of: Callable[[Graph], Entries], name: str) -> int:
    """`type`: print the types of name one a line, once it is in the graph; the exit code.

    It waits for name within the strategy's grace; exit code 1, printing nothing, when it never
    shows up (as upstream).
    """
    strategy.wait_until(lambda: types_of(entries_of(strategy.graph), name) is not None)
    types = types_of(entries_of(strategy.graph), name)
    if types is None:
        return 1
    for type_name in types:
        print(type_name)
    return 0
