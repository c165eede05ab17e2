"""make setup's packages built once per machine and content, copied into any workspace after that.

What colcon installs for a package depends only on the package's own files, the packages of the
workspace it is built against, and the toolchain. So a package's build is kept in
$XDG_CACHE_HOME/owl-kit-lab/builds under a digest of those inputs, and a workspace that needs the
same digest (a new clone, the class server's lab, a build after `make clean`) gets a copy instead of
a build: for the message packages and the C++ twin, code generation and compiling (about half of
colcon's job time on a 2-core machine); for a --symlink-install build of a Python package, colcon's
four runs of its setup.py (about 2 s of CPU each package). The text files and symlinks that name
the workspace (a launcher's interpreter, a CMake export naming the venv, the links of a
--symlink-install build into src/ and build/) name it through a placeholder in the cache.

    prebuilt_packages.py restore ROOT RECIPE PACKAGE_DIR...   names the packages still to build
    prebuilt_packages.py store ROOT RECIPE PACKAGE_DIR...     keeps what the workspace built of them

RECIPE is the build's command line (a different one is a different digest). Every package's files,
the digests of the workspace's packages it is built against (package.xml), requirements.txt, this
file, the compilers, cmake and the Python are in the digest too.
"""

from __future__ import annotations

import compileall
import functools
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ElementTree
from pathlib import Path

PLACEHOLDER = b'/@owl-kit-lab-workspace@'
RELOCATED = '.owl-relocated'  # in a cached copy: the texts and links that named the workspace
STAMP_SUFFIX = '.owl-prebuilt.sha256'  # install/<name> + this: the digest its copy was made from
UNUSED_FOR = 30 * 24 * 3600.0  # s: a cached build no workspace restored for this long is removed
TOOLS = (['cc', '--version'], ['c++', '--version'], ['cmake', '--version'])
# package.xml's dependencies a build reads (what a package only runs with does not change its build)
BUILD_DEPENDS = ('depend', 'build_depend', 'buildtool_depend', 'build_export_depend')


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


@functools.cache
def workspace_packages(root: Path) -> dict[str, Path]:
    """The workspace's packages by name: each package.xml under src/ and its folder (read once)."""
    found = {}
    for manifest in sorted((root / 'src').rglob('package.xml')):
        name = ElementTree.parse(manifest).findtext('name')
        if name:
            found[name.strip()] = manifest.parent
    return found


def build_dependencies(package_dir: Path, packages: dict[str, Path]) -> list[str]:
    """The workspace's packages the package is built against, by name, sorted."""
    manifest = ElementTree.parse(package_dir / 'package.xml').getroot()
    return sorted({(element.text or '').strip() for tag in BUILD_DEPENDS for element in manifest.iter(tag)}
                  & set(packages))


def sources_digest(package_dir: Path, packages: dict[str, Path], seen: dict[Path, str]) -> str:
    """A digest of the package's files and of those of every workspace package it is built against."""
    if package_dir not in seen:
        seen[package_dir] = 'in a dependency cycle'  # which colcon refuses to build anyway
        digest = hashlib.sha256(tree_digest(package_dir).encode())
        for name in build_dependencies(package_dir, packages):
            digest.update(f'\0{name}\0'.encode() + sources_digest(packages[name], packages, seen).encode())
        seen[package_dir] = digest.hexdigest()
    return seen[package_dir]


def package_digest(root: Path, package_dir: Path, recipe: str, tools: str,
                   seen: dict[Path, str] | None = None) -> str:
    """The digest a build of the package is kept under: what the build reads, the workspace's path aside."""
    sources = sources_digest(package_dir, workspace_packages(root), {} if seen is None else seen)
    digest = hashlib.sha256()
    for part in (sources, (root / 'requirements.txt').read_text(), Path(__file__).read_text(), recipe, tools):
        digest.update(part.encode() + b'\0')
    return digest.hexdigest()


def kept_folders(name: str, recipe: str) -> list[str]:
    """What a build of the package leaves: install/<name>, and build/<name> if it links into that."""
    folders = [f'install/{name}']
    if '--symlink-install' in recipe.split():
        folders.append(f'build/{name}')
    return folders


def entry(cache: Path, name: str, digest: str) -> Path:
    """The cache's folder for one build of a package."""
    return cache / f'{name}-{digest[:24]}'


def stamp(root: Path, name: str) -> Path:
    """The file that names the digest of the build in install/<name>."""
    return root / 'install' / (name + STAMP_SUFFIX)


def is_text(data: bytes) -> bool:
    """Whether a file's bytes are text (the way git tells: no NUL near the start)."""
    return b'\0' not in data[:8192]


def naming(folder: Path, root: bytes) -> list[str]:
    """What under folder names root: each text file ('text PATH') and each symlink ('link PATH') that does.

    A binary names it only in debug strings; a link is not followed.
    """
    found = []
    for parent, folders, files in os.walk(folder):
        for name in sorted(folders + files):
            path = Path(parent) / name
            relative = path.relative_to(folder)
            if path.is_symlink():
                if root in os.fsencode(os.readlink(path)):
                    found.append(f'link {relative}')
            elif path.is_file():
                data = path.read_bytes()
                if root in data and is_text(data):
                    found.append(f'text {relative}')
    return sorted(found)


def relocate(folder: Path, named: list[str], old: bytes, new: bytes) -> None:
    """Replace old by new in the named texts and links under folder (as naming() lists them)."""
    for line in named:
        kind, _, name = line.partition(' ')
        path = folder / name
        if kind == 'link':
            target = os.fsencode(os.readlink(path)).replace(old, new)
            path.unlink()
            path.symlink_to(os.fsdecode(target))
        else:
            path.write_bytes(path.read_bytes().replace(old, new))


def store(root: Path, cache: Path, package_dir: Path, digest: str, recipe: str) -> None:
    """Keep what a build of the package just made in the cache (placed whole, by one rename).

    Where the cache cannot be written (a read-only home), one line says so and the build is simply
    not kept: the workspace's own build is complete either way.
    """
    name = package_dir.name
    stamp(root, name).write_text(digest + '\n')
    target = entry(cache, name, digest)
    try:
        cache.mkdir(parents=True, exist_ok=True)
        if not target.is_dir():
            keep(root, kept_folders(name, recipe), cache, target)
        forget_unused(cache, name)
    except OSError as error:
        reason = error.strerror or str(error)
        print(f'setup: {name} is built but not kept for other workspaces ({cache}: {reason})',
              file=sys.stderr)


def keep(root: Path, folders: list[str], cache: Path, target: Path) -> None:
    """Copy root's folders into the cache as target, the workspace's path in them replaced by PLACEHOLDER."""
    staging = Path(tempfile.mkdtemp(prefix=f'.{target.name}-', dir=cache))
    try:
        copy = staging / target.name
        for folder in folders:
            shutil.copytree(root / folder, copy / folder, symlinks=True,
                            ignore=shutil.ignore_patterns('__pycache__'))
        named = naming(copy, bytes(root))
        relocate(copy, named, bytes(root), PLACEHOLDER)
        (copy / RELOCATED).write_text(''.join(f'{line}\n' for line in named))
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


def restore(root: Path, cache: Path, package_dir: Path, digest: str, recipe: str) -> bool:
    """Whether the package's build in root is (now) that of digest: there or copied from the cache."""
    name = package_dir.name
    folders = kept_folders(name, recipe)
    marker = stamp(root, name)
    if all((root / folder).is_dir() for folder in folders) and marker.is_file() \
            and marker.read_text().strip() == digest:
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
    compileall.compile_dir(copy / 'install', quiet=2, workers=0)  # quiet: stdout names what to build
    forget_build(root, name)  # what is there is of another digest or another kind of build
    for folder in folders:
        (root / folder).parent.mkdir(exist_ok=True)
        (copy / folder).rename(root / folder)
    shutil.rmtree(staging, ignore_errors=True)
    marker.write_text(digest + '\n')
    return True


def forget_build(root: Path, name: str) -> None:
    """Remove the package's install and build folders, of whichever kind of build.

    A build folder left configured for --symlink-install would symlink again; one without would not.
    """
    shutil.rmtree(root / 'install' / name, ignore_errors=True)
    shutil.rmtree(root / 'build' / name, ignore_errors=True)


def main(argv: list[str]) -> int:
    """Restore or store each package; restore prints those that need building."""
    if len(argv) < 4 or argv[0] not in ('restore', 'store'):
        print(__doc__.split('\n\n')[2], file=sys.stderr)
        return 2
    action, root, recipe = argv[0], Path(argv[1]).resolve(), argv[2]
    cache = cache_dir(dict(os.environ))
    tools = toolchain()
    seen: dict[Path, str] = {}
    for relative in argv[3:]:
        package_dir = root / relative
        digest = package_digest(root, package_dir, recipe, tools, seen)
        if action == 'store':
            store(root, cache, package_dir, digest, recipe)
        elif not restore(root, cache, package_dir, digest, recipe):
            forget_build(root, package_dir.name)
            print(relative)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
