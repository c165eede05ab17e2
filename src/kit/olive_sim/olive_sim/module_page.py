"""A simulated module's own web page, laid out on the real firmware's menus (spec §5).

The menus: System Status (device fields, live CPU, memory and network charts, Network Settings,
Device Control), Debug GUI (modules with an IMU: live Euler angles and a 3D view) and Log Monitor.

Served by owl_web from a thread of the module's own process at http://127.B.C.D:<port>/ for the
module address A.B.C.D (network_settings.py says why). Nothing runs for the page while no browser
watches: each live channel has a thread only while a page subscribes to it.

    GET  /api/device    device fields and Network Settings
    POST /api/network   {"address", "mask", "gateway"} (any of them): checked, then the page moves
    POST /api/restart   {}: Restart Services (the module's process starts again)
    POST /api/reboot    {}: Reboot Device (the same after a boot delay)
    /ws channels        system (1 Hz samples), orientation (25 Hz, modules with an IMU), log
"""

from __future__ import annotations

import errno
import os
import shutil
import threading
import time
from collections import deque
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from olive_kit.description import module_page, page_catalogue, page_host
from owl_common.periodic import PeriodicThread
from owl_common.quaternion import to_euler
from owl_web import codec
from owl_web.codec import ApiError
from owl_web.server import Request, Subscription, WebServer

from olive_sim import network_settings
from olive_sim.network_settings import NetworkSettings
from olive_sim.process_stats import ProcessSampler
from olive_sim.restart import BOOT_DELAY

if TYPE_CHECKING:
    from olive_sim.module_node import OliveModule

STATIC_DIR = Path(__file__).parent / 'static'
SYSTEM_RATE = 1.0        # Hz of the System Status samples
ORIENTATION_RATE = 25.0  # Hz of the Debug GUI's angles: smooth to the eye, little to send
HISTORY = 120            # samples a newly opened page gets (2 min at 1 Hz)
MOVE_GRACE = 0.5         # s the old address answers after an IP change, to send its answer
RESTART_GRACE = 0.3      # s between answering Restart/Reboot and stopping, for the same reason


class WatchedChannel:
    """A channel whose data is made and pushed at `rate` by a thread that runs only while pages watch."""

    def __init__(self, name: str, rate: float, make: Callable[[], dict[str, Any]],
                 alive: Callable[[], bool], first: Callable[[Subscription], None] | None = None) -> None:
        self.name = name
        self.rate = rate
        self.make = make
        self.alive = alive
        self.first = first  # sends a new subscriber what it needs before the pushes
        self._watchers: set[Subscription] = set()
        self._thread: PeriodicThread | None = None
        self._lock = threading.Lock()

    def open(self, subscription: Subscription) -> None:
        """Add a page: send it `first`'s data, then the pushes; the first page starts the thread."""
        if self.first is not None:
            self.first(subscription)
        with self._lock:
            self._watchers.add(subscription)
            if self._thread is None:
                self._thread = PeriodicThread(self.rate, self._push, f'page {self.name}', self.alive)

    def close(self, subscription: Subscription) -> None:
        """Remove a page; the last one to leave stops the thread."""
        with self._lock:
            self._watchers.discard(subscription)
            thread = self._thread if not self._watchers else None
            if thread is not None:
                self._thread = None
        if thread is not None:
            thread.stop()

    def stop(self) -> None:
        """Drop every page and stop the thread (the module's page is closing)."""
        with self._lock:
            thread, self._thread = self._thread, None
            self._watchers.clear()
        if thread is not None:
            thread.stop()

    @property
    def watched(self) -> bool:
        """Whether any page watches the channel now."""
        return bool(self._watchers)

    def _push(self) -> None:
        data = self.make()
        with self._lock:
            watchers = list(self._watchers)
        for watcher in watchers:
            watcher.send(data)


class ModulePage:
    """The page of one module; start() binds its address (OSError when it is taken)."""

    def __init__(self, module: OliveModule, settings: NetworkSettings, port: int) -> None:
        self.module = module
        self.settings = settings
        self.port = port
        self.sampler = ProcessSampler(module.traffic)
        self.samples: deque[dict[str, Any]] = deque(maxlen=HISTORY)
        self._lock = threading.Lock()  # one Network Settings change at a time
        alive = module.context.ok
        self.system = WatchedChannel('system', SYSTEM_RATE, self._system_sample, alive, self._send_history)
        self.orientation = WatchedChannel('orientation', ORIENTATION_RATE, self._orientation, alive)
        self._log_listeners: dict[Subscription, Callable[[dict[str, Any]], None]] = {}
        self.server: WebServer | None = None

    @property
    def url(self) -> str:
        """The page's address, http://127.B.C.D:<port>/ for the module address A.B.C.D (the port it got)."""
        if self.server is not None:
            return self.server.url
        return f'http://{page_host(self.settings.address)}:{self.port}/'

    @property
    def address(self) -> str:
        """Where a student opens the page: under the front door when it runs, else url."""
        return self.server.address if self.server is not None else self.url

    def start(self) -> None:
        """Serve the page at the module's address; OSError when that address and port are taken."""
        self.server = self._serve(self.settings.address)

    def stop(self) -> None:
        """Stop the live channels, the log listeners and the server."""
        self.system.stop()
        self.orientation.stop()
        for subscription in list(self._log_listeners):
            self._unwatch_log(subscription)
        with self._lock:
            server, self.server = self.server, None
        if server is not None:
            server.stop()

    def _serve(self, address: str) -> WebServer:
        """Serve the page for the module address A.B.C.D at 127.B.C.D, listed at the front door with it."""
        logger = self.module.get_logger()
        server = WebServer(self.module.get_name(), STATIC_DIR, self.port, page_host(address),
                           log=lambda line: logger.warning(f'web page: {line}'))
        server.join_front_door(module_page(self.module.module_type, self.module.namespace_name, address),
                               page_catalogue())
        server.route('GET', '/api/device', self._device)
        server.route('POST', '/api/network', self._network)
        server.route('POST', '/api/restart', lambda request: self._restart(request, 0.0))
        server.route('POST', '/api/reboot', lambda request: self._restart(request, BOOT_DELAY))
        server.channel('system', self.system.open, self.system.close)
        server.channel('log', self._watch_log, self._unwatch_log)
        if self.module.imu_orientation() is not None:
            server.channel('orientation', self.orientation.open, self.orientation.close)
        server.start()
        return server

    # ---- System Status ---------------------------------------------------------------------

    def _device(self, request: Request) -> dict[str, Any]:
        module = self.module
        storage = shutil.disk_usage(Path(__file__).parent)
        return {
            'device': {
                'Device Type': module.module_type,
                'Namespace': module.namespace_name,
                'Node': module.get_name(),
                'Process ID': os.getpid(),  # the simulated module is this process; a restart keeps it
                'Serial Number': module.serial,
                'Firmware version': module.firmware,
                'DCM version': module.firmware,
                'Software Patch': 'none (simulated module)',
                'Storage (GB)': f'{storage.used / 1e9:.1f} of {storage.total / 1e9:.1f}',
            },
            'network': self.settings.as_dict(),
            'url': self.url,
            'boot': module.boot_id,
            'debug': module.imu_orientation() is not None,
        }

    def _status(self) -> dict[str, Any]:
        return {'uptime': round(time.monotonic() - self.module.started),
                'temperature': round(self.module.temperature(), 1), 'boot': self.module.boot_id}

    def _system_sample(self) -> dict[str, Any]:
        sample = self.sampler.sample().__dict__
        self.samples.append(sample)
        return {'samples': [sample], **self._status()}

    def _send_history(self, subscription: Subscription) -> None:
        if not self.system.watched:  # samples of an earlier watch would leave a gap in the chart
            self.samples.clear()
            self.sampler.sample()  # the starting point of the first CPU and traffic rates
        subscription.send({'samples': list(self.samples), **self._status()})

    # ---- Network Settings ------------------------------------------------------------------

    def _network(self, request: Request) -> dict[str, Any]:
        body = request.json()
        codec.check_keys(body, network_settings.FIELDS)
        if not body:
            raise ApiError(400, f"nothing to change: give any of {', '.join(network_settings.FIELDS)}")
        with self._lock:
            try:
                new = network_settings.changed(self.settings, body)
            except ValueError as error:
                raise ApiError(400, str(error)) from None
            old_host, new_host = page_host(self.settings.address), page_host(new.address)
            old_server = self.server
            if new_host != old_host:
                try:
                    self.server = self._serve(new.address)
                except OSError as error:
                    if error.errno == errno.EADDRINUSE:
                        raise ApiError(409, f'Network IP {new.address} is in use: another module answers '
                                            f'at {new_host}:{self.port}') from None
                    raise ApiError(409, f'cannot serve at {new_host}:{self.port}: '
                                        f'{error.strerror or error}') from None
                # The answer leaves through the old address, which stops a moment later.
                if old_server is not None:
                    threading.Timer(MOVE_GRACE, old_server.stop).start()
            self.settings = new
        self.module.get_logger().info(
            f'network settings: IP {new.address}, mask {new.mask}, gateway {new.gateway}; '
            f'web page at {self.url}')
        return {'network': new.as_dict(), 'url': self.url}

    # ---- Device Control ----------------------------------------------------------------------

    def _restart(self, request: Request, delay: float) -> dict[str, Any]:
        codec.check_keys(request.json(), ())
        what = 'Reboot Device' if delay else 'Restart Services'
        boot = f' after a {delay:.0f} s boot' if delay else ''
        self.module.get_logger().info(f'{what}: restarting{boot}')
        self.module.request_restart(delay, RESTART_GRACE)
        return {'restarting': what, 'delay': delay}

    # ---- Debug GUI ---------------------------------------------------------------------------

    def _orientation(self) -> dict[str, Any]:
        q = self.module.imu_orientation()
        if q is None:
            return {}
        roll, pitch, yaw = to_euler(q)
        return {'roll': roll, 'pitch': pitch, 'yaw': yaw,
                'quaternion': {'x': q[0], 'y': q[1], 'z': q[2], 'w': q[3]}}

    # ---- Log Monitor -------------------------------------------------------------------------

    def _watch_log(self, subscription: Subscription) -> None:
        # Updates replace each other while a page is slow, so each carries the recent lines;
        # the page shows those it has not shown yet (by their number).
        book, boot = self.module.logbook, self.module.boot_id

        def send(_line: dict[str, Any]) -> None:
            subscription.send({'boot': boot, 'lines': book.lines()})

        self._log_listeners[subscription] = send
        subscription.send({'boot': boot, 'lines': book.listen(send)})

    def _unwatch_log(self, subscription: Subscription) -> None:
        listener = self._log_listeners.pop(subscription, None)
        if listener is not None:
            self.module.logbook.forget(listener)
