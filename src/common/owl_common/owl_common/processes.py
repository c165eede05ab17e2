"""Start ROS executables as child processes, watch their output, stop them cleanly.

Used by the system tests, the demo and the benchmarks, so each of them isolates itself the same
way: a ROS domain of its own (leased through a lock file, so concurrent runs on one machine never
share one) and discovery limited to this machine.
"""

from __future__ import annotations

import ctypes
import fcntl
import itertools
import os
import re
import shutil
import signal
import socket
import subprocess
import tempfile
import threading
import time
import xmlrpc.client
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import IO

# `ros2` verbs start a graph daemon per domain that outlives them, listening on this port + N.
ROS2_DAEMON_BASE_PORT = 11511
DAEMON_STOP_TIMEOUT = 10.0  # s: as `ros2 daemon stop` waits for the port
# Fast DDS maps domain N to UDP ports 7400 + 250 N and up; up to 101 stays clear of the
# Linux ephemeral range. 0 is left to the user's own shell.
DOMAIN_IDS = range(1, 102)
LEASE_DIR = Path(os.environ.get('OWL_DOMAIN_LEASE_DIR', '/tmp/owl-kit-lab-domains'))


def shared_folder(directory: Path) -> None:
    """Make directory a folder every account may add to, as /tmp is (mode 1777), if it is ours.

    The domain leases are machine-wide: on a class server each student's `owl check` leases from
    the same folder, and the class server holds every student's own domain there.
    """
    directory.mkdir(parents=True, exist_ok=True)
    made = directory.stat()
    if made.st_uid == os.geteuid() and made.st_mode & 0o7777 != 0o1777:
        directory.chmod(0o1777)  # also one made before leases were shared


def try_lock_file(directory: Path, ids: Sequence[int], start: int = 0,
                  rested: float = 0.0) -> tuple[int, IO[str]] | None:
    """The first free one of ids, with its lock file's handle; None when every one is held.

    The search counts from index start and wraps; an id is free when no process holds its lock file
    in directory, and it stays locked until the returned handle is closed (or the process ends). How
    concurrent runs on one machine share domains and test slots. With rested, an id whose lock file
    was touched (given_back) less than that many seconds ago is not free either.
    """
    shared_folder(directory)
    now = time.time()
    for offset in range(len(ids)):
        chosen = ids[(start + offset) % len(ids)]
        path = directory / f'{chosen}.lock'
        if rested and _modified_within(path, rested, now):
            continue
        # Read-only: a lock file another account made (a class server's, a classmate's) locks as well.
        handle = os.fdopen(os.open(path, os.O_RDONLY | os.O_CREAT, 0o644))
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            handle.close()
            continue
        return chosen, handle
    return None


def _modified_within(path: Path, seconds: float, now: float) -> bool:
    try:
        return now - path.stat().st_mtime < seconds
    except FileNotFoundError:
        return False


def given_back(handle: IO[str], path: Path) -> None:
    """Close a lock file's handle from try_lock_file, its time of modification now (see rested).

    A lock file another account made keeps its time: this account may not change it.
    """
    try:
        os.utime(path)
    except OSError:
        pass
    handle.close()


# A domain given back rests this long before it is leased again while another one is free: a
# stopped test's nodes stay in the domain's discovery data for seconds (a killed process's participant
# until its DDS lease runs out, a discovery bridge 10 s); `ros2 doctor` in a test once counted the
# turtle_teleop_key of the test before it in that domain. (One worker's next lease also moves on,
# below, but several workers' lease counters start close together and cross each other's domains.)
DOMAIN_REST = 15.0  # s

# Where this process's next lease starts looking: one domain further each time. A domain just given
# back may still hold what its last user left for seconds (a discovery bridge lingers 10 s, a killed
# process's participant until its DDS lease runs out); a test run's worker that took the first free
# domain from a fixed start used the same one for every test, so a test could meet the last one's.
LEASE_STARTS = itertools.count(os.getpid())


class DomainLease:
    """Exclusive use of one ROS_DOMAIN_ID on this machine until release()."""

    def __init__(self) -> None:
        start = next(LEASE_STARTS) % len(DOMAIN_IDS)
        # a domain that has rested, else (every free one given back lately) any free one
        leased = (try_lock_file(LEASE_DIR, DOMAIN_IDS, start, rested=DOMAIN_REST)
                  or try_lock_file(LEASE_DIR, DOMAIN_IDS, start))
        if leased is None:
            raise RuntimeError(f'all ROS domains {DOMAIN_IDS.start}..{DOMAIN_IDS.stop - 1} are in use')
        self.domain_id, handle = leased
        self._handle: IO[str] | None = handle

    def release(self) -> None:
        """Give the domain back (close the lock file, marked given back); a second call does nothing."""
        if self._handle is not None:
            given_back(self._handle, LEASE_DIR / f'{self.domain_id}.lock')
            self._handle = None


def isolated_env(domain_id: int, base: dict[str, str] | None = None,
                 discovery_range: str = 'LOCALHOST') -> dict[str, str]:
    """The environment for processes that must only see each other.

    With discovery_range SUBNET they see each other on other machines too.
    """
    env = dict(os.environ if base is None else base)
    env.update({
        'ROS_DOMAIN_ID': str(domain_id),
        'ROS_AUTOMATIC_DISCOVERY_RANGE': discovery_range,
        'PYTHONUNBUFFERED': '1',
        'RCUTILS_LOGGING_BUFFERED_STREAM': '1',
        'RCUTILS_COLORIZED_OUTPUT': '0',
    })
    env.pop('ROS_STATIC_PEERS', None)
    return env


def installed_executable(package: str, executable: str) -> Path:
    """<prefix>/lib/<package>/<executable> from the first AMENT_PREFIX_PATH entry that has it."""
    prefixes = [p for p in os.environ.get('AMENT_PREFIX_PATH', '').split(os.pathsep) if p]
    for prefix in prefixes:
        candidate = Path(prefix) / 'lib' / package / executable
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return candidate
    raise FileNotFoundError(
        f"no executable '{executable}' of package '{package}' under AMENT_PREFIX_PATH "
        '(is the workspace built and env.sh sourced?)')


PR_SET_PDEATHSIG = 1  # prctl option: the signal a process gets when its parent thread ends


def _prepare_child(default_sigint: bool, parent: int | None) -> Callable[[], None]:
    """What the child runs before exec.

    Children are stopped with Ctrl-C's signal as at a terminal, so they must not inherit an ignored
    SIGINT (what `nohup` or a script's background job gives us). And each gets SIGTERM when its
    parent dies: a test run, a demo or a benchmark that is killed (SIGKILL included) would
    otherwise leave its nodes running, in their own process groups, talking in a leased domain.
    The death signal follows the thread that started the child, so parent is None (no death
    signal) for a child started by a helper thread, which may end long before the child.
    """
    def prepare() -> None:
        if default_sigint:
            signal.signal(signal.SIGINT, signal.SIG_DFL)
        if parent is not None:
            ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
            if os.getppid() != parent:  # the parent died before the line above
                os.kill(os.getpid(), signal.SIGTERM)
    return prepare


def dies_with_this_process() -> Callable[[], None]:
    """preexec_fn for a child started with subprocess itself, e.g. on a pseudo-terminal.

    Like RosProcess's children, it gets SIGTERM when the calling thread ends.
    """
    return _prepare_child(False, os.getpid())


class RosProcess:
    """A child process in its own process group whose merged output is collected line by line."""

    def __init__(self, argv: list[str], env: dict[str, str], label: str | None = None,
                 echo: bool = False, cwd: str | None = None) -> None:
        self.argv = [str(a) for a in argv]
        self.label = label or Path(self.argv[0]).name
        self.echo = echo
        self.lines: list[str] = []
        self.last_signal: int | None = None
        self._changed = threading.Condition()
        self.popen = subprocess.Popen(
            self.argv, env=env, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT, text=True, errors='replace', bufsize=1,
            start_new_session=True,
            preexec_fn=_prepare_child(
                signal.getsignal(signal.SIGINT) == signal.SIG_IGN,
                os.getpid() if threading.current_thread() is threading.main_thread() else None))
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self.popen.stdout is not None
        for line in self.popen.stdout:
            line = line.rstrip('\n')
            if self.echo:
                print(f'[{self.label}] {line}', flush=True)
            with self._changed:
                self.lines.append(line)
                self._changed.notify_all()
        with self._changed:
            self._changed.notify_all()

    @property
    def pid(self) -> int:
        """The process id, which is also its process group id."""
        return self.popen.pid

    @property
    def output(self) -> str:
        """All output read so far, as one string (lines joined by newlines)."""
        with self._changed:
            return '\n'.join(self.lines)

    def running(self) -> bool:
        """Whether the process has not exited yet."""
        return self.popen.poll() is None

    def wait_for(self, pattern: str, timeout: float = 10.0, count: int = 1) -> list[re.Match]:
        """Wait until count output lines match the regex pattern; return those matches."""
        regex = re.compile(pattern)
        deadline = time.monotonic() + timeout
        with self._changed:
            while True:
                matches = [m for m in map(regex.search, self.lines) if m]
                if len(matches) >= count:
                    return matches[:count]
                remaining = deadline - time.monotonic()
                if remaining <= 0 or (not self._reader.is_alive() and self.popen.poll() is not None):
                    raise AssertionError(
                        f'{self.label}: waited {timeout:.1f} s for {count} line(s) matching '
                        f'{pattern!r}; exit code {self.popen.poll()}; output:\n{self.tail()}')
                self._changed.wait(min(remaining, 0.2))

    def tail(self, lines: int = 40) -> str:
        """The last lines of output, or "(none)"."""
        return '\n'.join(self.lines[-lines:]) or '(none)'

    def wait(self, timeout: float = 10.0) -> int:
        """Wait for the process to exit and its output to be read; return its exit code."""
        code = self.popen.wait(timeout)
        self._reader.join(timeout)
        return code

    def send_signal(self, sig: int = signal.SIGINT) -> None:
        """Signal the whole process group, as a terminal's Ctrl-C does."""
        if self.running():
            try:
                os.killpg(self.popen.pid, sig)
            except ProcessLookupError:
                pass

    def stop(self, timeout: float = 5.0) -> int:
        """SIGINT, then SIGTERM, then SIGKILL, each after timeout; return the exit code."""
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL):
            self.send_signal(sig)
            self.last_signal = sig
            try:
                return self.wait(timeout)
            except subprocess.TimeoutExpired:
                continue
        return self.wait(timeout)

    def stop_cleanly(self, timeout: float = 5.0) -> None:
        """stop(), and fail with the output's tail unless Ctrl-C alone ended it with exit code 0."""
        code = self.stop(timeout)
        assert self.last_signal is not None  # stop() sends SIGINT at least
        if code != 0:
            raise AssertionError(
                f'{self.label}: exit code {code} after {signal.Signals(self.last_signal).name}; '
                f'output:\n{self.tail()}')


class RosSandbox:
    """A set of processes sharing one private ROS domain; close() stops them all.

    With private_pages (the default), the pages its processes serve are listed in a pages folder
    of its own and start no front door (OWL_PAGES_DIR, OWL_FRONT_DOOR=off: owl_web.pages), so a
    test's pages never join the user's front door nor another test's; the demo shares the user's.
    """

    def __init__(self, echo: bool = False, discovery_range: str = 'LOCALHOST',
                 private_pages: bool = True) -> None:
        self._lease = DomainLease()
        self.domain_id = self._lease.domain_id
        self.env = isolated_env(self.domain_id, discovery_range=discovery_range)
        self.pages_dir: str | None = None
        if private_pages:
            self.pages_dir = tempfile.mkdtemp(prefix='owl-pages-')
            self.env.update({'OWL_PAGES_DIR': self.pages_dir, 'OWL_FRONT_DOOR': 'off'})
        self.echo = echo
        self.processes: list[RosProcess] = []

    def run(self, package: str, executable: str, *args: str, label: str | None = None,
            env: dict[str, str | None] | None = None) -> RosProcess:
        """Start an installed executable of a package, like `ros2 run package executable args`."""
        path = installed_executable(package, executable)
        return self.command([str(path), *args], label=label or executable, env=env)

    def command(self, argv: Iterable[str], label: str | None = None,
                env: dict[str, str | None] | None = None, cwd: str | None = None) -> RosProcess:
        """Start any command inside the sandbox's domain; env entries set to None are removed."""
        process_env = dict(self.env)
        for name, value in (env or {}).items():
            if value is None:
                process_env.pop(name, None)
            else:
                process_env[name] = value
        process = RosProcess(list(argv), process_env, label=label, echo=self.echo, cwd=cwd)
        self.processes.append(process)
        return process

    def close(self) -> None:
        """Stop the processes still running and the domain's ros2 daemon; free the domain.

        All but the first started stop side by side (a stop is mostly a node's own clean-up, about
        0.2 s); the first, most often the kit or the server the others use, stops after them, as a
        node that turns the servos' torque off at Ctrl-C needs the kit still there.
        """
        first, others = self.processes[:1], self.processes[1:]
        with ThreadPoolExecutor(len(others) + 1) as pool:
            daemon = pool.submit(stop_ros2_daemon, self.domain_id)
            for stop in [pool.submit(process.stop, 3.0) for process in others if process.running()]:
                stop.result()
            daemon.result()
        for process in first:
            if process.running():
                process.stop(3.0)
        if self.pages_dir is not None:  # a front door a test started leaves with its folder
            shutil.rmtree(self.pages_dir, ignore_errors=True)
            self.pages_dir = None
        self._lease.release()

    def __enter__(self) -> RosSandbox:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()


def stop_ros2_daemon(domain_id: int) -> None:
    """Stop the `ros2` daemon of a domain, if one runs, and wait until its port is free.

    The next user of the domain then starts with an empty graph cache instead of one remembering
    this sandbox's nodes. Asked over its XML-RPC interface (upstream's system.shutdown at /ros2cli/),
    as `ros2 daemon stop` asks it, without a process of its own (0.15 s of CPU each time).
    """
    port = ROS2_DAEMON_BASE_PORT + domain_id
    try:
        with socket.create_connection(('127.0.0.1', port), timeout=0.2):
            pass
    except OSError:
        return
    try:
        with xmlrpc.client.ServerProxy(f'http://127.0.0.1:{port}/ros2cli/') as daemon:
            daemon.system.shutdown()
    except (OSError, xmlrpc.client.Error):
        return  # not a daemon of ours, or gone meanwhile
    deadline = time.monotonic() + DAEMON_STOP_TIMEOUT
    while time.monotonic() < deadline:
        try:
            with socket.create_connection(('127.0.0.1', port), timeout=0.2):
                pass
        except OSError:
            return
        time.sleep(0.05)
