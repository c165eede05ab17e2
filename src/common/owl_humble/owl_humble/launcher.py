"""Start this domain's discovery bridge if it is not running (cheap: imports no DDS library).

Our tools call `ensure_discovery_bridge()` before they read the graph; see owl_humble/bridge.py.
They start it in open mode only (discovery range SUBNET, or static peers), where Humble modules can
be: a bridge in the domain makes a new participant's discovery slower (a fresh node saw a 20-node
graph complete after a median 0.36 s and p90 1.01 s with a bridge, against 0.23 s and 0.36 s
without), and in private mode no real module can be reached. humble_twin, a local stand-in for a
module, starts it in private mode itself (local_twin).
"""

from __future__ import annotations

import os
import socket
import subprocess
import sys

from owl_common.ros_env import discovery_range, static_peers


def bridge_address(environ: dict[str, str] | None = None, local_twin: bool = False) -> str | None:
    """The abstract socket name that the one bridge per user, domain and discovery range holds.

    None where no bridge is wanted: discovery off, another rmw than Fast DDS, private mode without
    static peers (unless for a local twin).
    """
    env = os.environ if environ is None else environ
    reach = discovery_range(env)
    peers = ';'.join(static_peers(env))
    if reach == 'OFF' or env.get('RMW_IMPLEMENTATION', 'rmw_fastrtps_cpp') != 'rmw_fastrtps_cpp':
        return None
    if reach == 'LOCALHOST' and not peers and not local_twin:
        return None
    return f'\0owl-discovery-bridge-{os.getuid()}-{env.get("ROS_DOMAIN_ID") or 0}-{reach}-{peers}'


def ensure_discovery_bridge(environ: dict[str, str] | None = None, local_twin: bool = False) -> bool:
    """Start the bridge in the background unless one runs or none is wanted; True if started here.

    One runs when a process holds the address that bridge_address gives (None: no bridge wanted).

    The address is bound here and handed to the child, so two callers racing cannot both start one.
    """
    env = dict(os.environ if environ is None else environ)
    address = bridge_address(env, local_twin)
    if address is None:
        return False
    holder = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        try:
            holder.bind(address)
        except OSError:
            return False
        subprocess.Popen(
            [sys.executable, '-m', 'owl_humble.bridge', '--fd', str(holder.fileno())],
            pass_fds=[holder.fileno()], start_new_session=True, stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        return True
    finally:
        holder.close()
