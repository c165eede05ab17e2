"""Names on the command line: node/topic name rules, hidden names, 'did you mean' hints."""

import difflib
from collections.abc import Callable, Iterable


def full_node_name(namespace: str, name: str) -> str:
    """'/' + 'talker' -> '/talker'; '/ns' + 'talker' -> '/ns/talker'."""
    return f"{namespace.rstrip('/')}/{name}"


def split_node_name(node_name: str) -> tuple[str, str]:
    """A node name (leading '/' optional) as (namespace, base name)."""
    full = node_name if node_name.startswith('/') else '/' + node_name
    namespace, _, name = full.rpartition('/')
    return namespace or '/', name


def is_hidden_node(full_name: str) -> bool:
    return full_name.rpartition('/')[2].startswith('_')


def is_hidden_name(name: str) -> bool:
    """A topic or service is hidden when any of its tokens starts with '_'."""
    return any(token.startswith('_') for token in name.split('/'))


def expand_topic_name(name: str) -> str:
    """Relative names resolve against the CLI node's namespace, the root."""
    return name if name.startswith('/') else '/' + name


def did_you_mean(name: str, candidates: Iterable[str]) -> str:
    """' (did you mean 'x'?)' for the closest candidate, or '' when nothing is close."""
    close = difflib.get_close_matches(name, list(candidates), n=1, cutoff=0.6)
    return f" (did you mean '{close[0]}'?)" if close else ''


class WaitingHint:
    """While a verb waits for a name (as upstream, forever), say so once on stderr after a grace
    period, and once more when a close name shows up: the name is probably mistyped."""

    def __init__(self, subject: str, name: str, grace: float) -> None:
        import time
        self._subject = subject  # e.g. "server for service '/ech'"
        self._name = name
        self._grace_end = time.monotonic() + grace
        self._said = self._suggested = False

    def update(self, candidates: Callable[[], Iterable[str]]) -> None:
        import sys
        import time
        if self._suggested or time.monotonic() < self._grace_end:
            return
        hint = did_you_mean(self._name, [c for c in candidates() if c != self._name])
        if hint or not self._said:
            print(f'No {self._subject} yet{hint}; still waiting (Ctrl-C to stop)', file=sys.stderr)
            self._said, self._suggested = True, bool(hint)
