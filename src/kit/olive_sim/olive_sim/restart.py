"""Restart Services and Reboot Device: a module process starts itself again.

The process replaces itself (exec) with the command line it was started with, so it keeps its
process id: `ros2 launch`, a test harness or a terminal still hold the same process, Ctrl-C still
reaches it, and its node comes back with the same names and parameters. Before the exec the node
is destroyed and ROS shut down as at Ctrl-C, so other nodes see the old participant leave.

What the module had that a restart keeps (the IP set on its page, a servo's shaft angle, which
does not move because software restarts) travels to the new process in one environment variable,
which the new process takes out of its environment at once.
"""

from __future__ import annotations

import faulthandler
import json
import os
import signal
import sys
import time
from typing import Any, NoReturn

HANDOVER_VARIABLE = 'OWL_MODULE_HANDOVER'
BOOT_DELAY = 5.0  # s a rebooting module is away (page and node), as a device's boot


def take_handover() -> dict[str, Any]:
    """What the process before this one handed over ({} on a first start).

    It is removed from the environment so that nothing this process starts inherits it.
    """
    text = os.environ.pop(HANDOVER_VARIABLE, '')
    if not text:
        return {}
    try:
        handover = json.loads(text)
    except ValueError:
        handover = None
    if not isinstance(handover, dict):
        print(f'{HANDOVER_VARIABLE} is not a JSON object: starting afresh', file=sys.stderr, flush=True)
        return {}
    return handover


def _stop_quietly(signum: int, frame: object) -> NoReturn:
    raise SystemExit(0)


def start_again(handover: dict[str, Any], delay: float = 0.0) -> NoReturn:
    """Exec this process's own command line with the handover, after delay s (a reboot).

    Call after the node is destroyed and ROS is shut down. Ctrl-C during the delay ends the
    process quietly, as it would have stopped the module.
    """
    faulthandler.cancel_dump_traceback_later()  # the clean-up watchdog: the clean-up is done
    signal.signal(signal.SIGINT, _stop_quietly)
    signal.signal(signal.SIGTERM, _stop_quietly)
    if delay > 0:
        time.sleep(delay)
    # An ignored signal stays ignored across exec; the new process must start as this one did.
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    environment = {**os.environ, HANDOVER_VARIABLE: json.dumps(handover)}
    sys.stdout.flush()
    sys.stderr.flush()
    os.execve(sys.executable, sys.orig_argv, environment)
