"""Who opened a loopback connection, from the kernel's socket table (owl_web.owner_only)."""

import os
import socket
import sys
from pathlib import Path

from owl_web.owner_only import OwnerOnly, socket_owner, table_address, wanted

SERVER, CLIENT = ('127.0.0.1', 8080), ('127.0.0.1', 53956)


def table_row(number, local, remote, uid):
    return (f'   {number}: {local} {remote} 01 00000000:00000000 00:00000000 00000000 {uid:5}        0 '
            f'{700 + number} 1')


TABLE = '\n'.join([
    '  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid  timeout inode',
    table_row(0, table_address(*SERVER), '00000000:0000', 0),  # listening
    table_row(1, table_address(*SERVER), table_address(*CLIENT), 0),  # the server's accepted socket
    table_row(2, table_address(*CLIENT), table_address(*SERVER), 1001),  # the student's
])


class Connection:
    """A transport's two addresses, as asyncio and uvloop give them."""

    def __init__(self, ours, peer):
        self.extra = {'sockname': ours, 'peername': peer}

    def get_extra_info(self, name):
        return self.extra[name]


def test_addresses_are_written_as_the_kernel_writes_them():
    expected = '0100007F:1F90' if sys.byteorder == 'little' else '7F000001:1F90'
    assert table_address('127.0.0.1', 8080) == expected
    assert table_address('127.42.0.8', 8042).endswith(':1F6A')


def test_the_connecting_side_is_the_row_whose_local_address_is_the_peer():
    assert socket_owner(TABLE, CLIENT, SERVER) == 1001  # the student who connected
    assert socket_owner(TABLE, SERVER, CLIENT) == 0  # the server's own accepted socket
    assert socket_owner(TABLE, CLIENT, ('127.0.0.1', 8081)) is None
    assert socket_owner('', CLIENT, SERVER) is None


def test_a_real_connection_is_found_as_this_account_and_another_account_is_refused():
    with socket.create_server(('127.0.0.1', 0)) as listener:
        with socket.create_connection(listener.getsockname()):
            accepted, _ = listener.accept()
            with accepted:
                ours, peer = accepted.getsockname(), accepted.getpeername()
                table = Path('/proc/net/tcp').read_text()
                assert socket_owner(table, peer, ours) == os.getuid()
                assert OwnerOnly(on=True).refusal(Connection(ours, peer)) is None
                refusal = OwnerOnly(on=True, uid=os.getuid() + 1).refusal(Connection(ours, peer))
                assert refusal is not None
                assert refusal.startswith(f'refused: these pages are for account uid {os.getuid() + 1} only '
                                          f'(OWL_PAGES_OWNER_ONLY=1) and account uid {os.getuid()} opened')


def test_off_serves_everyone_and_on_refuses_what_it_cannot_place(tmp_path):
    assert OwnerOnly(on=False).refusal(Connection(('127.0.0.1', 1), ('127.0.0.1', 2))) is None
    gone = OwnerOnly(on=True).refusal(Connection(('127.0.0.1', 1), ('127.0.0.1', 2)))
    assert gone is not None
    assert gone.endswith('a socket the kernel no longer lists opened this connection; '
                                              'open your own pages through your own front door')
    unix = OwnerOnly(on=True).refusal(Connection('/run/owl.sock', ''))
    assert unix is not None
    assert unix.startswith('refused: the account that opened this connection is unknown')
    unreadable = OwnerOnly(on=True, table=tmp_path / 'no-table')
    assert unreadable.refusal(Connection(('127.0.0.1', 1), ('127.0.0.1', 2))).startswith(
        'refused: the account that opened this connection is unknown')
    assert wanted({'OWL_PAGES_OWNER_ONLY': '1'})
    assert not wanted({'OWL_PAGES_OWNER_ONLY': 'yes'})
    assert not wanted({})
