"""Mistyped names on the command line, while a verb waits for them.

(The rules of node and topic names live in owl_common.graph, the 'did you mean' hint in
owl_common.hints.)
"""

import sys
import time
from collections.abc import Callable, Iterable

from owl_common.hints import did_you_mean


class WaitingHint:
    """The notice on stderr while a verb waits (as upstream, forever) for a name that may be mistyped.

    It is said once after a grace period (`grace`, seconds), and once more when a close name shows
    up: the name is then probably mistyped.
    """

    def __init__(self, subject: str, name: str, grace: float) -> None:
        self._subject = subject  # e.g. "server for service '/ech'"
        self._name = name
        self._grace_end = time.monotonic() + grace
        self._said = self._suggested = False

    def update(self, candidates: Callable[[], Iterable[str]]) -> None:
        """Call at each retry: print the notice when due; candidates() lists the names seen so far.

        candidates is only called once the grace period is over and until a close name was found.
        """
        if self._suggested or time.monotonic() < self._grace_end:
            return
        hint = did_you_mean(self._name, [c for c in candidates() if c != self._name])
        if hint or not self._said:
            print(f'No {self._subject} yet{hint}; still waiting (Ctrl-C to stop)', file=sys.stderr)
            self._said, self._suggested = True, bool(hint)
