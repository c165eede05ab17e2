"""Names on the command line: node/topic name rules, hidden names, 'did you mean' hints."""

import difflib
from collections.abc import Iterable


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
