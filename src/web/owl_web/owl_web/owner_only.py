"""Pages for their own account only: who opened a loopback connection, as the kernel's socket table says.

On a machine that several accounts share (a class server), 127.0.0.1 is everyone's: a student's
terminal could open a classmate's robot view or front door by its port, watch the classmate's camera
and drive their servos. With OWL_PAGES_OWNER_ONLY=1 (the class server sets it for every student),
each page server and the front door answer only connections that a process of their own account
opened; any other gets 403 and one line. A class server's browser never connects to a page itself:
the student's own server (jupyter-server-proxy, running as the student) does.

Linux lists every TCP socket of the machine, with its owner's uid, in /proc/net/tcp (readable by
every account): the connecting side is the row whose local address is our peer's and whose remote
address is ours. Reading the table costs about a millisecond, so each connection is looked up once.
Our servers listen on IPv4 loopback addresses only (owl_web.server), so the IPv4 table is enough.
"""

from __future__ import annotations

import os
import socket
import struct
import weakref
from collections.abc import Mapping
from pathlib import Path
from typing import Any

VARIABLE = 'OWL_PAGES_OWNER_ONLY'
SOCKET_TABLE = Path('/proc/net/tcp')
UID_FIELD = 7  # sl, local_address, rem_address, st, tx:rx queue, tr:when, retrnsmt, uid, ...


def wanted(environ: Mapping[str, str] | None = None) -> bool:
    """Whether the environment asks for pages of their own account only (OWL_PAGES_OWNER_ONLY=1)."""
    return (os.environ if environ is None else environ).get(VARIABLE) == '1'


def table_address(host: str, port: int) -> str:
    """An IPv4 address and port as /proc/net/tcp writes them: 0100007F:1F90 for 127.0.0.1:8080.

    The kernel prints the address's four bytes as one number in the machine's own byte order.
    """
    return f'{struct.unpack("=I", socket.inet_aton(host))[0]:08X}:{port:04X}'


def socket_owner(table: str, local: tuple[str, int], remote: tuple[str, int]) -> int | None:
    """The uid that owns the socket at local connected to remote, per /proc/net/tcp's text; None if absent."""
    key = (table_address(*local), table_address(*remote))
    for line in table.splitlines()[1:]:
        fields = line.split()
        if len(fields) > UID_FIELD and (fields[1], fields[2]) == key:
            return int(fields[UID_FIELD])
    return None


class OwnerOnly:
    """The refusal of a connection from another account, when owner-only is on; one lookup per connection."""

    def __init__(self, on: bool, uid: int | None = None, table: Path = SOCKET_TABLE) -> None:
        self.on = on
        self.uid = os.getuid() if uid is None else uid
        self.table = table
        self._verdicts: weakref.WeakKeyDictionary[Any, str | None] = weakref.WeakKeyDictionary()

    @classmethod
    def from_environment(cls, environ: Mapping[str, str] | None = None) -> OwnerOnly:
        """On when OWL_PAGES_OWNER_ONLY=1, for the account this process runs as."""
        return cls(wanted(environ))

    def refusal(self, transport: Any) -> str | None:
        """Why a connection (an asyncio or uvloop transport) may not be served, or None when it may."""
        if not self.on or transport is None:
            return None
        if transport not in self._verdicts:
            self._verdicts[transport] = self._judge(transport.get_extra_info('sockname'),
                                                    transport.get_extra_info('peername'))
        return self._verdicts[transport]

    def _judge(self, ours: Any, peer: Any) -> str | None:
        try:
            uid = socket_owner(self.table.read_text(), (peer[0], peer[1]), (ours[0], ours[1]))
        except (OSError, TypeError, IndexError, ValueError) as error:  # not an IPv4 TCP connection
            return f'refused: the account that opened this connection is unknown ({error})'
        if uid == self.uid:
            return None
        opener = f'account uid {uid}' if uid is not None else 'a socket the kernel no longer lists'
        return (f'refused: these pages are for account uid {self.uid} only ({VARIABLE}=1) and '
                f'{opener} opened this connection; open your own pages through your own front door')
