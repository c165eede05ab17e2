"""make setup's packages built once per machine: the message packages and the C++ twin.

Generating a package's message code and compiling it is most of a workspace's build (on a 2-core
machine, about half of colcon's job time), and what it installs depends only on the package's own
files and the toolchain. So these packages are built without --symlink-install, their install
folder is kept in $XDG_CACHE_HOME/owl-kit-lab/builds under a digest of those inputs, and a
workspace that needs the same digest (a new clone, the class server's lab, a build after
`make clean`) gets a copy instead of a build. The few text files that name the workspace (a
launcher's interpreter, a CMake export naming the venv) name it through a placeholder in the cache.

    prebuilt_packages.py restore ROOT RECIPE PACKAGE_DIR...   names the packages still to build
    prebuilt_packages.py store ROOT RECIPE PACKAGE_DIR...     keeps what the workspace built of them

RECIPE is the build's command line (a different one is a different digest). Every package's files,
requirements.txt, this file, the compilers, cmake and the Python are in the digest too.
"""

from __future__ import annotations

import compileall
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PLACEHOLDER = b'/@owl-kit-lab-workspace@'
RELOCATED = '.owl-relocated'  # in a cached copy: the files whose text named the workspace
STAMP_SUFFIX = '.owl-prebuilt.sha256'  # install/<name> + this: the digest its copy was made from
UNUSED_FOR = 30 * 24 * 3600.0  # s: a cached build no workspace restored for this long is removed
TOOLS = (['cc', '--version'], ['c++', '--version'], ['cmake', '--version'])


def cache_dir(environ: dict[str, str]) -> Path:
    """Where the builds are kept: beside the camera's panorama (olive_sim.camera_render)."""
    base = environ.get('XDG_CACHE_HOME') or str(Path(environ.get('HOME', '~')).expanduser() / '.cache')
    return Path(base) / 'owl-kit-lab' / 'builds'


def tree_digest(folder: Path) -> str:
    """A digest of a folder's files: their names relative to it and their contents."""
    digest = hashlib.sha256()
    for path in sorted(folder.rglob('*')):
        if '__pycache__' in path.parts or not path.is_file():
            continue
        digest.update(str(path.relative_to(folder)).encode() + b'\0')
        digest.update(path.read_bytes() + b'\0')
    return digest.hexdigest()


def toolchain() -> str:
    """The first line of each build tool's version, and the Python the build generates code for."""
    lines = []
    for command in TOOLS:
        try:
            done = subprocess.run(command, capture_output=True, text=True, check=False)
            lines.append(done.stdout.splitlines()[0] if done.stdout else f'{command[0]}: none')
        except FileNotFoundError:
            lines.append(f'{command[0]}: none')
    lines.append(f'{sys.version} {sys.base_prefix} {os.uname().machine}')
    return '\n'.join(lines)


def package_digest(root: Path, package_dir: Path, recipe: str, tools: str) -> str:
    """The digest a build of the package is kept under: what the build reads, the workspace's path aside."""
    digest = hashlib.sha256()
    for part in (tree_digest(package_dir), (root / 'requirements.txt').read_text(),
                 Path(__file__).read_text(), recipe, tools):
        digest.update(part.encode() + b'\0')
    return digest.hexdigest()


def entry(cache: Path, name: str, digest: str) -> Path:
    """The cache's folder for one build of a package."""
    return cache / f'{name}-{digest[:24]}'


def stamp(root: Path, name: str) -> Path:
    """The file that names the digest of the build in install/<name>."""
    return root / 'install' / (name + STAMP_SUFFIX)


def is_text(data: bytes) -> bool:
    """Whether a file's bytes are text (the way git tells: no NUL near the start)."""
    return b'\0' not in data[:8192]


def relocate(folder: Path, names: list[str], old: bytes, new: bytes) -> None:
    """Replace old by new in the named files under folder."""
    for name in names:
        path = folder / name
        path.write_bytes(path.read_bytes().replace(old, new))


def texts_naming(folder: Path, root: bytes) -> list[str]:
    """The text files under folder whose contents name root (binaries name it only in debug strings)."""
    found = []
    for path in sorted(folder.rglob('*')):
        if path.is_file() and not path.is_symlink():
            data = path.read_bytes()
            if root in data and is_text(data):
                found.append(str(path.relative_to(folder)))
    return found


def store(root: Path, cache: Path, package_dir: Path, digest: str) -> None:
    """Keep install/<name> of a build just made in the cache (placed whole, by one rename).

    Where the cache cannot be written (a read-only home), one line says so and the build is simply
    not kept: the workspace's own install is complete either way.
    """
    name = package_dir.name
    stamp(root, name).write_text(digest + '\n')
    target = entry(cache, name, digest)
    try:
        cache.mkdir(parents=True, exist_ok=True)
        if not target.is_dir():
            keep(root, root / 'install' / name, cache, target)
        forget_unused(cache, name)
    except OSError as error:
        reason = error.strerror or str(error)
        print(f'setup: {name} is built but not kept for other workspaces ({cache}: {reason})',
              file=sys.stderr)


def keep(root: Path, installed: Path, cache: Path, target: Path) -> None:
    """Copy installed into the cache as target, the workspace's path in its texts replaced by PLACEHOLDER."""
    staging = Path(tempfile.mkdtemp(prefix=f'.{installed.name}-', dir=cache))
    try:
        copy = staging / installed.name
        shutil.copytree(installed, copy, symlinks=True, ignore=shutil.ignore_patterns('__pycache__'))
        relocated = texts_naming(copy, bytes(root))
        relocate(copy, relocated, bytes(root), PLACEHOLDER)
        (copy / RELOCATED).write_text(''.join(f'{line}\n' for line in relocated))
        try:
            copy.rename(target)
        except OSError:
            if not target.is_dir():
                raise
            # another setup stored the same build meanwhile
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def forget_unused(cache: Path, name: str) -> None:
    """Remove the package's cached builds that no workspace restored for UNUSED_FOR."""
    now = time.time()
    for old in cache.glob(f'{name}-*'):
        if old.is_dir() and now - old.stat().st_mtime > UNUSED_FOR:
            shutil.rmtree(old, ignore_errors=True)


def restore(root: Path, cache: Path, package_dir: Path, digest: str) -> bool:
    """Whether install/<name> is (now) the build of digest: already there or copied from the cache."""
    name = package_dir.name
    installed = root / 'install' / name
    marker = stamp(root, name)
    if installed.is_dir() and marker.is_file() and marker.read_text().strip() == digest:
        return True
    source = entry(cache, name, digest)
    if not (source / RELOCATED).is_file():
        return False
    os.utime(source)  # in use: not forgotten
    (root / 'install').mkdir(exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f'.{name}-', dir=root / 'install'))
    copy = staging / name
    # Copied with the current time, as a build made now would leave them: what compares a package's
    # sources with its install (owl check, colcon's users) must not take a fresh clone's sources as newer.
    shutil.copytree(source, copy, symlinks=True, copy_function=shutil.copy)
    relocate(copy, (copy / RELOCATED).read_text().splitlines(), PLACEHOLDER, bytes(root))
    (copy / RELOCATED).unlink()
    compileall.compile_dir(copy, quiet=2, workers=0)  # quiet: stdout names what to build
    shutil.rmtree(installed, ignore_errors=True)
    shutil.rmtree(root / 'build' / name, ignore_errors=True)  # a build folder of another kind of build
    copy.rename(installed)
    shutil.rmtree(staging, ignore_errors=True)
    marker.write_text(digest + '\n')
    return True


def main(argv: list[str]) -> int:
    """Restore or store each package; restore prints those that need building."""
    if len(argv) < 4 or argv[0] not in ('restore', 'store'):
        print(__doc__.split('\n\n')[2], file=sys.stderr)
        return 2
    action, root, recipe = argv[0], Path(argv[1]).resolve(), argv[2]
    cache = cache_dir(dict(os.environ))
    tools = toolchain()
    for relative in argv[3:]:
        package_dir = root / relative
        digest = package_digest(root, package_dir, recipe, tools)
        if action == 'store':
            store(root, cache, package_dir, digest)
        elif not restore(root, cache, package_dir, digest):
            # Its old install and build go: a build folder configured for --symlink-install would
            # symlink again.
            shutil.rmtree(root / 'install' / package_dir.name, ignore_errors=True)
            shutil.rmtree(root / 'build' / package_dir.name, ignore_errors=True)
            print(relative)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
