"""`import cv2` that works on a machine without the desktop libraries OpenCV's GUI build needs.

The venv's cv2 is opencv-python, the GUI build, so that cv2.imshow opens a real window. Its native
module needs the system's libGL and glib (packages libgl1, libglib2.0-0), which a minimal Linux
(a container, a server) may lack; then `import cv2` would fail with a traceback. scripts/bootstrap.sh
installs the headless build of the same version into <venv>/opencv-headless, copies this module
into site-packages and adds a .pth line that calls install(). On the first `import cv2` of a
process, the finder below loads the GUI build's native module once: if that fails, it puts the
headless folder first on sys.path and says so on stderr in one line. Deciding per process, not at
setup, means installing the libraries later turns the GUI build on without another `make setup`.
"""

from __future__ import annotations

import os
import sys

HEADLESS_DIR = os.path.join(sys.prefix, 'opencv-headless')
APT_HINT = "'sudo apt install libgl1 libglib2.0-0'"


def native_module(package_dir: str) -> str | None:
    """The compiled cv2 module inside a cv2 package folder (cv2.abi3.so in the PyPI wheels)."""
    try:
        names = sorted(os.listdir(package_dir))
    except OSError:
        return None
    for name in names:
        if name.startswith('cv2.') and name.endswith('.so'):
            return os.path.join(package_dir, name)
    return None


def gui_build_problem() -> str | None:
    """Why the cv2 on sys.path cannot load here, in one line; None if it loads or there is none."""
    import ctypes
    from importlib.machinery import PathFinder

    spec = PathFinder.find_spec('cv2')
    if spec is None or not spec.submodule_search_locations:
        return None
    for folder in spec.submodule_search_locations:
        library = native_module(folder)
        if library is not None:
            try:
                # The same dlopen the import does next; a missing system library fails it here.
                ctypes.CDLL(library)
            except OSError as error:
                return str(error).splitlines()[0]
            return None
    return None


def notice(problem: str) -> str:
    return (f"OpenCV's GUI build cannot load here ({problem}): cv2 is its headless build, "
            f'whose cv2.imshow opens no window; for windows: {APT_HINT}')


class ChooseOpenCVBuild:
    """A sys.meta_path entry that acts once, on the first `import cv2`, and then removes itself."""

    @classmethod
    def find_spec(cls, fullname: str, path: object = None, target: object = None) -> None:
        if fullname != 'cv2':
            return None
        sys.meta_path.remove(cls)
        if os.path.isdir(HEADLESS_DIR):
            problem = gui_build_problem()
            if problem is not None:
                sys.path.insert(0, HEADLESS_DIR)
                print(f'cv2: {notice(problem)}', file=sys.stderr)
        return None  # the usual finders import cv2, from the folder chosen above


def install() -> None:
    """Called by the .pth line at every start of the venv's Python; costs nothing until cv2 is imported."""
    if ChooseOpenCVBuild not in sys.meta_path:
        sys.meta_path.insert(0, ChooseOpenCVBuild)


def main() -> None:
    """For bootstrap.sh: print the notice if this machine falls back, nothing if it does not."""
    problem = gui_build_problem()
    if problem is not None:
        print(notice(problem))


if __name__ == '__main__':
    main()
