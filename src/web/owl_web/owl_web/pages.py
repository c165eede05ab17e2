"""Which of our pages run on this machine: the register the front door reads.

Every page server that joins the front door (rqt, the robot view, `owl windows`, each simulated
module's page) writes one small JSON file into a folder of the user's own while it serves, and
removes it when it stops; a page killed without a word leaves its file behind, and its process id
says it is gone. The folder also keeps the catalogue (the pages the kit knows, with the command
that starts each, so a stopped page can say how to start it) and the front door's own address.

The folder is private to its user (mode 0700): $OWL_PAGES_DIR, else $XDG_RUNTIME_DIR/owl-kit-lab-pages,
else /tmp/owl-kit-lab-pages-<uid>. On a machine shared by a class, each student's pages are then
listed by that student's front door only. Plain Python: the front door and `owl pages` share it.
"""

from __future__ import annotations

import errno
import fcntl
import json
import os
import re
import signal
import socket
import stat
import subprocess
import sys
import tempfile
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

# The front door's address on 127.0.0.1 unless OWL_FRONT_DOOR_PORT says otherwise (another free one
# when it is taken).
FRONT_DOOR_PORT = 8090
# A mount is the first segment of a page's path under the front door: /robot-view/, /servo-pan/.
MOUNT = re.compile(r'[a-z0-9][a-z0-9-]{0,62}')
RESERVED_MOUNTS = frozenset({'api', 'lib', 'owl', 'static', 'ws'})  # the front door's own paths
FRONT_DOOR_FILE = 'front-door.json'
CATALOGUE_FILE = 'catalogue.json'
PAGE_PREFIX = 'page-'


class PagesError(Exception):
    """The pages' folder cannot be used (not ours, not private): one line saying what to do."""


@dataclass(frozen=True)
class Page:
    """A page: where it sits under the front door, what it is called and how it is started.

    A running page also has its own address (url) and its server's process id; a page of the
    catalogue has neither. address is a module's address in the course (10.42.0.8), else ''.
    """

    mount: str
    title: str
    start: str
    address: str = ''
    url: str = ''
    pid: int = 0

    def __post_init__(self) -> None:
        if not isinstance(self.mount, str) or not MOUNT.fullmatch(self.mount) \
                or self.mount in RESERVED_MOUNTS:
            raise ValueError(f"'{self.mount}' cannot be a page's path: lower-case letters, digits and '-', "
                             f"not one of {', '.join(sorted(RESERVED_MOUNTS))}")

    @classmethod
    def from_json(cls, data: Any) -> Page:
        """A page from its JSON object; ValueError saying what is wrong."""
        if not isinstance(data, dict):
            raise ValueError('not a JSON object')
        known = {f.name: f.type for f in fields(cls)}
        unknown = sorted(set(data) - set(known))
        if unknown:
            raise ValueError(f"unknown key '{unknown[0]}'")
        for key in ('mount', 'title', 'start'):
            if not isinstance(data.get(key), str):
                raise ValueError(f"'{key}' must be a string")
        if not isinstance(data.get('pid', 0), int) or not isinstance(data.get('url', ''), str) \
                or not isinstance(data.get('address', ''), str):
            raise ValueError("'pid' must be a number, 'url' and 'address' strings")
        return cls(**data)


@dataclass(frozen=True)
class PageState:
    """A page as the front door lists it: running now (its server answers) or not.

    course_address is a module's address in the course (the catalogue's); page.address is where it
    is now (a module moved by its Network Settings).
    """

    page: Page
    running: bool
    course_address: str = ''

    def as_json(self) -> dict[str, Any]:
        """The page for GET api/pages and `owl pages`."""
        page = self.page
        return {'mount': page.mount, 'title': page.title, 'running': self.running, 'path': f'{page.mount}/',
                'url': page.url if self.running else '', 'address': page.address, 'start': page.start}


def pages_dir(environ: Mapping[str, str] | None = None) -> Path:
    """The user's pages folder (the module's docstring says which); not created here."""
    env = os.environ if environ is None else environ
    if env.get('OWL_PAGES_DIR'):
        return Path(env['OWL_PAGES_DIR'])
    runtime = env.get('XDG_RUNTIME_DIR')
    if runtime and Path(runtime).is_dir():
        return Path(runtime) / 'owl-kit-lab-pages'
    return Path(tempfile.gettempdir()) / f'owl-kit-lab-pages-{os.getuid()}'


def private_folder(folder: Path) -> Path:
    """folder, made if missing, once it is a folder of this user's that nobody else may read or write.

    PagesError otherwise: in a shared /tmp another user could have made it first, to read or forge
    which pages run.
    """
    try:
        folder.mkdir(mode=0o700, parents=True, exist_ok=True)
        info = folder.lstat()
    except OSError as error:
        raise PagesError(f'cannot use the pages folder {folder}: {error.strerror or error}') from None
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid() or info.st_mode & 0o077:
        raise PagesError(f'the pages folder {folder} is not a private folder of yours (mode 0700); '
                         'remove it, or choose another with OWL_PAGES_DIR')
    return folder


def write_json(path: Path, data: Any) -> None:
    """Write data as JSON in one step: a reader sees the old file or the new one, never half of one."""
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix='.', suffix='.tmp')
    try:
        with os.fdopen(handle, 'w') as file:
            json.dump(data, file)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def read_json(path: Path) -> Any:
    """The JSON in path, or None when it is missing or not JSON (a file being replaced is never half-read)."""
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def register(page: Page, folder: Path) -> None:
    """Say that page runs (its url and pid set), in place of an earlier entry of the same mount."""
    write_json(private_folder(folder) / f'{PAGE_PREFIX}{page.mount}.json', asdict(page))


def unregister(page: Page, folder: Path) -> None:
    """Remove page's entry, unless another server has registered that mount since (a module that moved)."""
    path = folder / f'{PAGE_PREFIX}{page.mount}.json'
    data = read_json(path)
    if isinstance(data, dict) and data.get('url') == page.url and data.get('pid') == page.pid:
        path.unlink(missing_ok=True)


def registered(folder: Path, log: Callable[[str], None] | None = None) -> dict[str, Page]:
    """Every entry in the folder as mount -> Page; an entry that cannot be read is skipped (and logged)."""
    found = {}
    try:
        paths = sorted(folder.glob(f'{PAGE_PREFIX}*.json'))
    except OSError:
        return {}
    for path in paths:
        try:
            page = Page.from_json(read_json(path))
        except (ValueError, TypeError) as error:
            if log is not None:
                log(f'ignoring {path.name}: {error}')
            continue
        found[page.mount] = page
    return found


def write_catalogue(pages: list[Page], folder: Path) -> None:
    """Keep the pages that can be started (a page that joins the front door brings the kit's list)."""
    path = private_folder(folder) / CATALOGUE_FILE
    data = [asdict(page) for page in pages]
    if read_json(path) != data:
        write_json(path, data)


def catalogue(folder: Path) -> list[Page]:
    """The pages the kit knows, in the order the front door lists them ([] before any page joined)."""
    data = read_json(folder / CATALOGUE_FILE)
    pages = []
    for entry in data if isinstance(data, list) else []:
        try:
            pages.append(Page.from_json(entry))
        except (ValueError, TypeError):
            continue
    return pages


def process_alive(pid: int) -> bool:
    """Whether a process of that id exists (it may be another user's)."""
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def port_answers(url: str, timeout: float = 0.3) -> bool:
    """Whether something accepts a TCP connection at the url's host and port."""
    parts = urlsplit(url)
    try:
        with socket.create_connection((parts.hostname or '127.0.0.1', parts.port or 80), timeout=timeout):
            return True
    except OSError:
        return False


def page_states(folder: Path, answering: Callable[[str], bool] = port_answers,
                log: Callable[[str], None] | None = None) -> list[PageState]:
    """Every page to list: the catalogue's in its order, then any other registered one by mount.

    A page runs when its entry's process lives and its address answers; a page that stopped keeps
    what its entry said (a module's moved address, say) so it can say how to start it again.
    """
    known = {page.mount: page for page in catalogue(folder)}
    entries = registered(folder, log)
    states = []
    for mount in [*known, *sorted(set(entries) - set(known))]:
        entry = entries.get(mount)
        page = entry or known[mount]
        if entry is not None and not page.start and mount in known:
            page = Page(**{**asdict(entry), 'start': known[mount].start})
        running = entry is not None and process_alive(entry.pid) and answering(entry.url)
        states.append(PageState(page, running, known[mount].address if mount in known else page.address))
    return states


@dataclass(frozen=True)
class FrontDoorRecord:
    """The front door's address and process, as the process that started it wrote them."""

    url: str
    pid: int


def front_door_record(folder: Path) -> FrontDoorRecord | None:
    """The front door of this folder's pages if its process lives and its address answers, else None."""
    data = read_json(folder / FRONT_DOOR_FILE)
    if not isinstance(data, dict) or not isinstance(data.get('url'), str) \
            or not isinstance(data.get('pid'), int):
        return None
    record = FrontDoorRecord(data['url'], data['pid'])
    return record if process_alive(record.pid) and port_answers(record.url) else None


# ---- the front door's process --------------------------------------------------------------------

def front_door_wanted(environ: Mapping[str, str] | None = None) -> bool:
    """Whether pages start a front door: OWL_FRONT_DOOR=off leaves each page at its own address only."""
    return (os.environ if environ is None else environ).get('OWL_FRONT_DOOR', 'on') != 'off'


def preferred_port(environ: Mapping[str, str]) -> int:
    """OWL_FRONT_DOOR_PORT (0: any free one), else FRONT_DOOR_PORT; ValueError for anything else."""
    text = environ.get('OWL_FRONT_DOOR_PORT', '') or str(FRONT_DOOR_PORT)
    if not text.isdigit() or int(text) > 65535:
        raise ValueError(f"OWL_FRONT_DOOR_PORT must be a port number 0..65535, got '{text}'")
    return int(text)


def ensure_front_door(folder: Path, environ: Mapping[str, str] | None = None) -> str:
    """The front door's URL for the pages in folder, started in the background when none runs.

    Its port is OWL_FRONT_DOOR_PORT's or 8090, or a free one when that is taken by something else.
    The address is bound here and handed to the child, so two pages starting at once start one front
    door, and the caller can print the address at once (a connection waits until the child accepts
    it). PagesError, ValueError or OSError say in one line why it cannot start.
    """
    env = dict(os.environ if environ is None else environ)
    port = preferred_port(env)
    private_folder(folder)
    with open(folder / 'front-door.lock', 'w') as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        running = front_door_record(folder)
        if running is not None:
            return running.url
        listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        try:
            listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            try:
                listener.bind(('127.0.0.1', port))
            except OSError as error:
                if error.errno != errno.EADDRINUSE or port == 0:
                    raise
                listener.bind(('127.0.0.1', 0))
            listener.listen(128)
            url = f'http://127.0.0.1:{listener.getsockname()[1]}/'
            with open(folder / 'front-door.log', 'ab') as log:
                child = subprocess.Popen(
                    [sys.executable, '-m', 'owl_web.front_door', '--fd', str(listener.fileno()),
                     '--pages-dir', str(folder)],
                    pass_fds=[listener.fileno()], start_new_session=True, stdin=subprocess.DEVNULL,
                    stdout=log, stderr=log, env=env)
            write_json(folder / FRONT_DOOR_FILE, {'url': url, 'pid': child.pid})
            return url
        finally:
            listener.close()


def stop_front_door(folder: Path) -> bool:
    """Ask the front door of the pages in folder to stop (SIGTERM); True when one was running."""
    record = front_door_record(folder)
    if record is None:
        return False
    try:
        os.kill(record.pid, signal.SIGTERM)
    except ProcessLookupError:
        return False
    return True
