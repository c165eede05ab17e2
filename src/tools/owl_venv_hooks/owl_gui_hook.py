"""The venv's start-up hook for the course's GUI libraries: which OpenCV build, and windows without a display.

scripts/bootstrap.sh copies this module into the venv's site-packages with a .pth line that calls
install() at every start of the venv's Python. install() only puts a finder on sys.meta_path that
waits for the first `import cv2` or `import pygame`; nothing else is done before that, and nothing
imported but the windows folder's module (the standard library only).
It has two jobs; neither changes a line of the program that imports the library.

1. Which OpenCV build. The venv's cv2 is opencv-python, the GUI build, so that cv2.imshow opens a
   real window. Its native module needs the system's libGL and glib (libgl1, libglib2.0-0), which a
   minimal Linux may lack; bootstrap.sh also installs the headless build of the same version into
   <venv>/opencv-headless. At the first `import cv2` the GUI build's native module is loaded once:
   if that fails, the headless folder goes first on sys.path. Where a display is available this
   says so in one line on stderr (the fallback notice below); without one it is silent, as there
   would be no window either way (the headless windows below say that). Deciding per process, not
   at setup, means installing the libraries later turns the GUI build on without another setup.

2. Headless windows. Without a display, opencv-python's Qt aborts the process at the first
   cv2.imshow ("could not connect to display", exit code 134) and pygame opens an offscreen window
   that receives no keys, amid ALSA and XDG noise. In a process without a display this hook makes:
   - cv2: imshow, namedWindow, waitKey, waitKeyEx, pollKey, destroyWindow, destroyAllWindows and
     the other window functions work without a window. The first window prints one line on stderr
     (what happened, where to see the camera instead). waitKey(delay) waits delay ms and returns
     -1, as the real one does when no key is pressed; waitKey(0) waits for a key as the real one
     does: without the seam below nothing can send one, so it says once that Ctrl-C ends the wait.
     Where cv2 fell back to its headless build (whose window functions raise "not implemented")
     its windows are headless too, silently: the fallback notice has said that.
   - pygame: SDL's video and audio drivers are 'dummy' (set before SDL starts, unless the program
     chose drivers itself), so no window and no ALSA/XDG lines; the first pygame.display.set_mode
     prints one line (its window gets no keys, how to drive the servos instead).
   Whether a display is available: cv2 needs DISPLAY (the wheel's Qt has only its X11 plugin,
   which XWayland serves); pygame needs DISPLAY or WAYLAND_DISPLAY. OWL_HEADLESS=1 makes windows
   headless anyway and OWL_HEADLESS=0 leaves them real (for tests). Where a display is available
   nothing is patched; only QT_QPA_FONTDIR, which cv2's loader points at a font folder its wheel
   does not ship, is pointed at /usr/share/fonts after the import (unless it named a folder),
   which stops the wheel's Qt from printing "QFontDatabase: Cannot find font directory" ten times
   per window.

  The seam (the browser view of these windows, `owl windows`) is the windows folder, OWL_WINDOWS_DIR:
  src/common/owl_windows/owl_windows/folder.py is its contract and code, which this hook loads at
  the first headless window (`make setup` copies it into the venv beside this module).
"""

from __future__ import annotations

import os
import sys
from typing import TYPE_CHECKING

from owl_windows.folder import (
    DEFAULT_FPS,
    KeyReader,
    WindowsFolder,
    cv2_key_code,
    is_number,
    program_name,
    say,
    window_file,
    windows_fps,
    windows_root,
)

if TYPE_CHECKING:  # for the annotations only: this module is imported at every start of Python
    from collections.abc import Callable, Mapping, Sequence
    from importlib.abc import Loader
    from importlib.machinery import ModuleSpec
    from types import ModuleType
    from typing import Any, TypedDict

    from numpy import uint8
    from numpy.typing import NDArray

    class CvWindow(TypedDict):
        """A headless cv2 window: its flags, the size of its last image, its trackbars' positions."""

        flags: int
        size: tuple[int, int]
        trackbars: dict[str, int]

HEADLESS_DIR = os.path.join(sys.prefix, 'opencv-headless')
APT_HINT = "'sudo apt install libgl1 libglib2.0-0'"
FONT_DIR = '/usr/share/fonts'
RQT_HINT = 'To see the camera, run rqt and open Plugins > Visualization > Image View'
WINDOWS_HINT = "To see it in a browser, run 'owl windows'"
SERVO_HINT = ('To move the servos without keys: stop it, call /olive/servo/pan/setTorqueEnable and '
              'publish goals on /olive/servo/pan/goal/position (and tilt) with rqt or '
              'ros2 service call / ros2 topic pub')


# --- start-up: the finder ------------------------------------------------------------------------

SEEN: set[str] = set()  # the libraries whose first import this process has seen


class GuiImportHook:
    """A sys.meta_path entry that acts on the first `import cv2` and the first `import pygame`."""

    @classmethod
    def find_spec(cls, fullname: str, path: Sequence[str] | None = None,
                  target: ModuleType | None = None) -> ModuleSpec | None:
        """At the first import of cv2 or pygame: its spec, with a loader that patches it; else None.

        None leaves the import to the usual finders: any other module, a later import, nothing to patch.
        """
        if path is not None or fullname not in ('cv2', 'pygame') or fullname in SEEN:
            return None
        SEEN.add(fullname)  # before anything else: cv2's own loader imports 'cv2' again
        if len(SEEN) == 2:
            sys.meta_path.remove(cls)
        patch = prepare_cv2() if fullname == 'cv2' else prepare_pygame()
        if patch is None:
            return None  # the usual finders import it untouched
        spec = find_spec_after(cls, fullname, target)
        if spec is None or spec.loader is None:
            return None
        # The loader is duck-typed (create_module, exec_module), as the import system asks no more.
        spec.loader = PatchingLoader(spec.loader, patch)  # type: ignore[assignment]
        return spec


def find_spec_after(finder: object, fullname: str, target: ModuleType | None,
                    path: Sequence[str] | None = None) -> ModuleSpec | None:
    """The spec the other finders on sys.meta_path give, as the import would find it without us."""
    for other in list(sys.meta_path):
        if other is finder or not hasattr(other, 'find_spec'):
            continue
        spec = other.find_spec(fullname, path, target)
        if spec is not None:
            return spec
    return None


class PatchingLoader:
    """The module's own loader, then patch(module) once the module is complete."""

    def __init__(self, loader: Loader, patch: Callable[[ModuleType], None]) -> None:
        self.loader = loader
        self.patch = patch

    def create_module(self, spec: ModuleSpec) -> ModuleType | None:
        """The module object as the wrapped loader makes it (None: Python's default one)."""
        return self.loader.create_module(spec)

    def exec_module(self, module: ModuleType) -> None:
        """Run the module with the wrapped loader, then apply the patch to the finished module."""
        self.loader.exec_module(module)
        # cv2's __init__ swaps modules around while loading; what `import` hands out is in sys.modules.
        self.patch(sys.modules.get(module.__name__, module))

    def __getattr__(self, name: str) -> Any:
        return getattr(self.loader, name)


def install() -> None:
    """Called by the .pth line at every start of the venv's Python; costs nothing until cv2 or pygame."""
    if GuiImportHook not in sys.meta_path:
        sys.meta_path.insert(0, GuiImportHook)


# --- job 1: which OpenCV build --------------------------------------------------------------------

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
    """The fallback notice: why the GUI build cannot load here, and what to install for windows."""
    return (f"OpenCV's GUI build cannot load here ({problem}): cv2 is its headless build, "
            f'whose cv2.imshow opens no window; for windows: {APT_HINT}')


def prepare_cv2() -> Callable[[ModuleType], None]:
    """Before cv2 is imported: choose the build; the patch to apply after the import."""
    reason = headless_reason('cv2', os.environ)
    fell_back = False
    if os.path.isdir(HEADLESS_DIR):
        problem = gui_build_problem()
        if problem is not None:
            fell_back = True
            sys.path.insert(0, HEADLESS_DIR)
            if reason is None:  # without a display the window line says all there is to say
                print(f'cv2: {notice(problem)}', file=sys.stderr)
    if reason is None and not fell_back:
        return keep_font_dir(os.environ.get('QT_QPA_FONTDIR'))
    # The headless build's window functions raise "not implemented": headless windows either way,
    # silent when the fallback notice already said that imshow opens no window.
    return lambda cv2: patch_cv2(cv2, reason if reason is not None else '')


def keep_font_dir(before: str | None) -> Callable[[ModuleType], None]:
    """The patch for real windows: QT_QPA_FONTDIR back on a font folder that exists, for the wheel's Qt.

    cv2's loader points QT_QPA_FONTDIR at a folder the wheel does not ship, and Qt then prints ten
    lines per window about missing fonts. before is the variable's value before the import.
    """

    def patch(cv2: ModuleType) -> None:
        if before and os.path.isdir(before):
            os.environ['QT_QPA_FONTDIR'] = before  # the user's choice, which the loader overwrote
        elif not os.path.isdir(os.environ.get('QT_QPA_FONTDIR', '')) and os.path.isdir(FONT_DIR):
            # (A missing folder may also come from a parent process's cv2 loader, through the environment.)
            os.environ['QT_QPA_FONTDIR'] = FONT_DIR

    return patch


# --- job 2: headless windows, the pure parts ------------------------------------------------------

def headless_reason(library: str, environ: Mapping[str, str]) -> str | None:
    """Why this library's windows cannot be shown (for the notice), or None when they can."""
    forced = environ.get('OWL_HEADLESS', '')
    if forced == '1':
        return 'OWL_HEADLESS=1'
    if forced == '0':
        return None
    if library == 'cv2':
        if environ.get('DISPLAY'):
            return None
        if environ.get('WAYLAND_DISPLAY'):
            return "DISPLAY is not set, and OpenCV's windows need X11 (XWayland)"
        return 'DISPLAY is not set'
    if environ.get('DISPLAY') or environ.get('WAYLAND_DISPLAY'):
        return None
    return 'neither DISPLAY nor WAYLAND_DISPLAY is set'


def setting_problems(environ: Mapping[str, str]) -> list[str]:
    """One line per OWL_HEADLESS or OWL_WINDOWS_FPS value that is ignored."""
    problems = []
    forced = environ.get('OWL_HEADLESS', '')
    if forced not in ('', '0', '1'):
        problems.append(f'OWL_HEADLESS must be 1 (no windows) or 0 (real windows), not {forced!r}: ignored')
    fps = environ.get('OWL_WINDOWS_FPS', '')
    if fps and not (is_number(fps) and 0 < float(fps) < float('inf')):
        problems.append(f'OWL_WINDOWS_FPS must be a number of frames per second above 0, not {fps!r}: '
                        f'using {DEFAULT_FPS:g}')
    return problems


def cv2_notice(program: str, reason: str, window: str, windows_dir: str | None) -> str:
    """The line said at a program's first cv2 window without a display, and where to see it instead.

    With windows_dir (the process's folder) that is the browser view of `owl windows`, else rqt.
    """
    line = (f"{program}: no display ({reason}), so the window {window!r} is not shown; the program "
            'runs on without it. ')
    if windows_dir:
        return line + f'{WINDOWS_HINT} (its frames go to {windows_dir})'
    return line + RQT_HINT


def pygame_notice(program: str, reason: str, windows_dir: str | None) -> str:
    """The line said at a program's first pygame window without a display, and how to drive it instead.

    With windows_dir (the process's folder): `owl windows` or its keys file; else the servos' topics.
    """
    line = (f'{program}: no display ({reason}), so the pygame window is not shown and gets no key '
            'presses; the program runs on without them. ')
    if windows_dir:
        return line + ("To see it and press its keys in a browser, run 'owl windows'; or append key "
                       f"events to {os.path.join(windows_dir, 'keys')} ('down left', 'up left')")
    return line + SERVO_HINT


def displayable(image: object) -> NDArray[uint8]:
    """The 8-bit image cv2.imshow would show for an array: 16-bit / 256, float x 255 (clipped)."""
    import numpy

    array = numpy.asarray(image)
    if array.ndim == 3 and array.shape[2] == 1:
        array = array[:, :, 0]
    if array.ndim not in (2, 3) or (array.ndim == 3 and array.shape[2] not in (3, 4)):
        raise ValueError(f'an image of shape {array.shape} cannot be shown')
    if array.ndim == 3 and array.shape[2] == 4:
        array = array[:, :, :3]  # the window shows no transparency
    if array.dtype == numpy.uint8:
        return array
    if array.dtype == numpy.uint16:
        return (array >> 8).astype(numpy.uint8)
    if array.dtype.kind == 'f':
        return numpy.clip(numpy.nan_to_num(array) * 255.0, 0, 255).astype(numpy.uint8)
    if array.dtype.kind in 'iub':
        return numpy.clip(array, 0, 255).astype(numpy.uint8)
    raise ValueError(f'an image of type {array.dtype} cannot be shown')


# --- job 2: the seam ------------------------------------------------------------------------------

SETTINGS_CHECKED: list[bool] = []


class Seam:
    """What headless windows of one library share: the notice, the windows folder, the key reader."""

    def __init__(self, reason: str, library: str) -> None:
        self.reason = reason
        self.program = program_name(sys.argv)
        if not SETTINGS_CHECKED:
            SETTINGS_CHECKED.append(True)  # once per process, for cv2 and pygame together
            for problem in setting_problems(os.environ):
                say(f'owl_gui_hook: {problem}')
        root = windows_root(dict(os.environ))
        self.folder = WindowsFolder(root, self.program, windows_fps(os.environ)) if root else None
        self.library = library
        self.noticed = False
        self.reader: KeyReader | None = None

    def first_window(self, notice_line: Callable[[str | None], str]) -> None:
        """At every window: the notice once (unless silent), the folder made."""
        if self.folder is not None:
            self.folder.make()
        if not self.noticed:
            self.noticed = True
            if self.reason:
                folder = self.folder.path if self.folder is not None and self.folder.made else None
                say(notice_line(folder))

    def key_events(self, known: Callable[[str], bool]) -> list[tuple[bool, str]]:
        """The key events appended since the last call, [] before the folder is made.

        known (a key name -> whether this library can deliver it) is fixed by the first call.
        """
        if self.folder is None or not self.folder.made:
            return []
        if self.reader is None:
            self.reader = KeyReader(self.folder.keys_path, known)
        return self.reader.events()

    def flush_due(self) -> None:
        """Write the frames held back by the rate limit whose interval is over, if there is a folder."""
        if self.folder is not None and self.folder.made:
            self.folder.flush_due()


# --- job 2: headless cv2 --------------------------------------------------------------------------

def patch_cv2(cv2: Any, reason: str) -> None:
    """Replace cv2's window functions with ones that need no display (see the module's docstring)."""
    HeadlessCv2(cv2, reason).install()


class HeadlessCv2:
    """cv2's window functions without a display: windows kept as state, frames and keys through the seam."""

    def __init__(self, cv2: Any, reason: str) -> None:
        self.cv2 = cv2
        self.seam = Seam(reason, 'cv2')
        self.windows: dict[str, CvWindow] = {}  # name -> flags, size, trackbars
        self.keys: list[int] = []
        self.said_wait_forever = False

    def install(self) -> None:
        """Put these window functions in cv2's place (nothing() for the others), where cv2 has them."""
        names = ('imshow', 'namedWindow', 'waitKey', 'waitKeyEx', 'pollKey', 'destroyWindow',
                 'destroyAllWindows', 'resizeWindow', 'moveWindow', 'setWindowTitle',
                 'setWindowProperty', 'getWindowProperty', 'getWindowImageRect', 'setMouseCallback',
                 'startWindowThread', 'createTrackbar', 'getTrackbarPos', 'setTrackbarPos',
                 'setTrackbarMin', 'setTrackbarMax', 'selectROI', 'selectROIs', 'displayOverlay',
                 'displayStatusBar', 'createButton', 'addText', 'setOpenGlContext', 'setOpenGlDrawCallback',
                 'updateWindow', 'imshowEx')
        for name in names:
            if hasattr(self.cv2, name):
                setattr(self.cv2, name, getattr(self, name, self.nothing))

    # -- windows

    def window(self, name: object, flags: int | None = None) -> CvWindow:
        """The named window's state; a new window is made (flags default 1) and counts for the notice."""
        name = str(name)
        if name not in self.windows:
            self.windows[name] = {'flags': flags if flags is not None else 1, 'size': (0, 0),
                                  'trackbars': {}}
            self.seam.first_window(lambda folder: cv2_notice(self.seam.program, self.seam.reason,
                                                             name, folder))
        return self.windows[name]

    def namedWindow(self, winname: str, flags: int = 1) -> None:
        """cv2.namedWindow: make the window, with its flags."""
        self.window(winname, flags)

    def imshow(self, winname: str, mat: object) -> None:
        """cv2.imshow: cv2.error for what OpenCV refuses; else keep the size, send the image to the seam."""
        import numpy

        if isinstance(mat, self.cv2.UMat):
            mat = mat.get()
        if not isinstance(mat, numpy.ndarray):
            raise self.cv2.error(f'OpenCV(headless window): Bad argument in function imshow: mat is '
                                 f'not a numpy array but {type(mat).__name__}')
        if mat.size == 0:
            raise self.cv2.error("OpenCV(headless window): (-215:Assertion failed) size.width>0 && "
                                 "size.height>0 in function 'imshow'")
        try:
            image = displayable(mat)
        except ValueError as error:
            raise self.cv2.error(f'OpenCV(headless window): {error} in function imshow') from None
        window = self.window(winname)
        window['size'] = (image.shape[1], image.shape[0])
        if self.seam.folder is not None:
            self.seam.folder.show(window_file('cv2', str(winname)), image, self.jpeg, lambda i: i.copy())

    def jpeg(self, image: NDArray[uint8]) -> bytes:
        """The image as JPEG bytes (quality 90); b'' if OpenCV cannot encode it."""
        ok, data = self.cv2.imencode('.jpg', image, [int(self.cv2.IMWRITE_JPEG_QUALITY), 90])
        return data.tobytes() if ok else b''

    def destroyWindow(self, winname: str) -> None:
        """cv2.destroyWindow: forget the window and remove its file from the seam."""
        if self.windows.pop(str(winname), None) is not None and self.seam.folder is not None:
            self.seam.folder.discard(window_file('cv2', str(winname)))

    def destroyAllWindows(self) -> None:
        """cv2.destroyAllWindows: destroyWindow for every window."""
        for name in list(self.windows):
            self.destroyWindow(name)

    def getWindowProperty(self, winname: str, prop_id: int) -> float:
        """cv2.getWindowProperty: visible while the window exists, its autosize flag; 0.0 for the others.

        Visible is 1.0 or 0.0 (a loop waiting for the window's close runs on); any other property of an
        unknown window is -1.0.
        """
        window = self.windows.get(str(winname))
        if prop_id == getattr(self.cv2, 'WND_PROP_VISIBLE', 4):
            return 1.0 if window is not None else 0.0  # as if shown: a loop waiting for its close runs on
        if window is None:
            return -1.0
        if prop_id == getattr(self.cv2, 'WND_PROP_AUTOSIZE', 1):
            return 1.0 if window['flags'] == 1 else 0.0
        return 0.0

    def getWindowImageRect(self, winname: str) -> tuple[int, int, int, int]:
        """cv2.getWindowImageRect: (0, 0, width, height) of the last image shown; all -1 for no window."""
        window = self.windows.get(str(winname))
        return (0, 0, *window['size']) if window is not None else (-1, -1, -1, -1)

    def startWindowThread(self) -> int:
        """cv2.startWindowThread: 0, no thread to start without a window."""
        return 0

    def createTrackbar(self, trackbarName: str, windowName: str, value: int, count: int,
                       onChange: object = None) -> None:
        """cv2.createTrackbar: keep its position; onChange is never called, as nothing can move it."""
        self.window(windowName)['trackbars'][str(trackbarName)] = int(value)

    def getTrackbarPos(self, trackbarname: str, winname: str) -> int:
        """cv2.getTrackbarPos: the position last set, 0 for an unknown trackbar."""
        return self.window(winname)['trackbars'].get(str(trackbarname), 0)

    def setTrackbarPos(self, trackbarname: str, winname: str, pos: int) -> None:
        """cv2.setTrackbarPos: keep the new position."""
        self.window(winname)['trackbars'][str(trackbarname)] = int(pos)

    def selectROI(self, *args: object, **kwargs: object) -> tuple[int, int, int, int]:
        """cv2.selectROI: the empty rectangle at once, as when the user cancels the selection."""
        return (0, 0, 0, 0)  # as when the selection is cancelled

    def selectROIs(self, *args: object, **kwargs: object) -> tuple[()]:
        """cv2.selectROIs: no rectangles at once, as when the user cancels the selection."""
        return ()

    def nothing(self, *args: object, **kwargs: object) -> None:
        """resizeWindow, moveWindow, setWindowTitle, setMouseCallback ...: nothing to do without a window."""
        return None

    # -- keys

    def take_key(self) -> int:
        """The next key pressed through the seam, as the GUI build's code; -1 if none is waiting.

        Frames held back by the rate limit are written first: the program looks for keys between frames.
        """
        self.seam.flush_due()
        for down, key in self.seam.key_events(lambda key: cv2_key_code(key) is not None):
            if down:
                self.keys.append(cv2_key_code(key))  # type: ignore[arg-type]  # not None: known keys only
        return self.keys.pop(0) if self.keys else -1

    def waitKeyEx(self, delay: int = 0) -> int:
        """cv2.waitKeyEx: the next key from the seam, waiting up to delay ms (0 or less: for ever); or -1."""
        import time

        key = self.take_key()
        if key != -1:
            return key
        delay = int(delay)
        reading = self.seam.folder is not None and self.seam.folder.made
        if delay <= 0 and not reading and not self.said_wait_forever:
            self.said_wait_forever = True
            say(f'{self.seam.program}: cv2.waitKey({delay}) waits for a key press, which no window '
                'can receive here: Ctrl-C stops the program')
        deadline = time.monotonic() + delay / 1000.0 if delay > 0 else None
        while True:
            remaining = None if deadline is None else deadline - time.monotonic()
            if remaining is not None and remaining <= 0:
                return -1
            # Keys are polled every 10 ms; without a keys file nothing can come before the deadline.
            step = 0.01 if reading else 3600.0
            time.sleep(step if remaining is None else min(step, remaining))
            key = self.take_key()
            if key != -1:
                return key

    def waitKey(self, delay: int = 0) -> int:
        """cv2.waitKey: as waitKeyEx, with only the low byte of the key's code."""
        key = self.waitKeyEx(delay)
        return key & 0xff if key != -1 else -1

    def pollKey(self) -> int:
        """cv2.pollKey: the next key from the seam without waiting, or -1."""
        return self.take_key()


# --- job 2: headless pygame -----------------------------------------------------------------------

def prepare_pygame() -> Callable[[ModuleType], None] | None:
    """Before pygame is imported: SDL's dummy drivers without a display; the patch, or None."""
    reason = headless_reason('pygame', os.environ)
    if reason is None:
        return None
    # SDL reads these when it starts (pygame.init / display.init), after the import.
    os.environ.setdefault('SDL_VIDEODRIVER', 'dummy')
    os.environ.setdefault('SDL_AUDIODRIVER', 'dummy')
    return lambda pygame: HeadlessPygame(pygame, reason).install()


class HeadlessPygame:
    """pygame's display, event and key functions for a process without a display, wired to the seam."""

    def __init__(self, pygame: Any, reason: str) -> None:
        self.pygame = pygame
        self.seam = Seam(reason, 'pygame')
        self.held: set[int] = set()
        self.real: dict[str, Callable[..., Any]] = {}

    def install(self) -> None:
        """Wrap pygame's display, event and key functions; the originals are kept in self.real."""
        pygame = self.pygame
        for module, names in ((pygame.display, ('set_mode', 'flip', 'update', 'quit')),
                              (pygame.event, ('get', 'poll', 'wait', 'peek', 'pump')),
                              (pygame.key, ('get_pressed', 'get_mods'))):
            for name in names:
                self.real[f'{module.__name__}.{name}'] = getattr(module, name)
        real = self.real
        key: Any  # declared for mypy, as the class PressedKeys below subclasses key.ScancodeWrapper
        display, event, key = pygame.display, pygame.event, pygame.key

        def set_mode(*args: object, **kwargs: object) -> Any:
            surface = real['pygame.display.set_mode'](*args, **kwargs)
            self.seam.first_window(lambda folder: pygame_notice(self.seam.program, self.seam.reason, folder))
            self.capture()
            return surface

        def flip() -> None:
            real['pygame.display.flip']()
            self.capture()

        def update(*args: object, **kwargs: object) -> None:
            real['pygame.display.update'](*args, **kwargs)
            self.capture()

        def display_quit() -> None:
            if self.seam.folder is not None:
                self.seam.folder.discard(window_file('pygame', ''))
            real['pygame.display.quit']()

        real_quit = pygame.quit

        def pygame_quit() -> None:
            if self.seam.folder is not None:
                self.seam.folder.discard(window_file('pygame', ''))
            real_quit()

        def reading(name: str) -> Callable[..., Any]:
            function = real[f'pygame.event.{name}']

            def read_keys_first(*args: object, **kwargs: object) -> Any:
                self.inject()
                return function(*args, **kwargs)

            read_keys_first.__doc__ = function.__doc__
            return read_keys_first

        def wait(timeout: int = 0) -> Any:
            import time

            # SDL's own wait would block in C, where no key from the seam could reach it.
            deadline = time.monotonic() + timeout / 1000.0 if timeout > 0 else None
            while True:
                self.inject()
                found = real['pygame.event.poll']()
                if found.type != pygame.NOEVENT:
                    return found
                if deadline is not None and time.monotonic() >= deadline:
                    return found
                time.sleep(0.01)

        # The keyboard state changes only when events are pumped, as SDL's does: a key read from the
        # seam between a loop's event.get() and its get_pressed() is held only after its KEYDOWN.
        def get_pressed() -> Any:
            pressed = PressedKeys(real['pygame.key.get_pressed']())
            pressed.held = frozenset(self.held)
            return pressed

        def get_mods() -> int:
            return real['pygame.key.get_mods']() | self.mods()

        class PressedKeys(key.ScancodeWrapper):
            """get_pressed()'s tuple, with the keys held through the seam pressed too."""

            held: frozenset[int] = frozenset()

            def __getitem__(self, index: object) -> Any:
                if isinstance(index, int) and index in self.held:
                    return True
                return super().__getitem__(index)

        display.set_mode, display.flip, display.update, display.quit = set_mode, flip, update, display_quit
        pygame.quit = pygame_quit
        for name in ('get', 'poll', 'peek', 'pump'):
            setattr(event, name, reading(name))
        event.wait = wait
        key.get_pressed, key.get_mods = get_pressed, get_mods

    def capture(self) -> None:
        """Send the display's content to the seam, once set_mode has made the window."""
        folder = self.seam.folder
        surface = self.pygame.display.get_surface()
        if folder is None or surface is None or not self.seam.noticed:
            return
        folder.show(window_file('pygame', ''), surface, self.png, lambda s: s.copy())

    def png(self, surface: Any) -> bytes:
        """The surface as PNG bytes."""
        import io

        data = io.BytesIO()
        self.pygame.image.save(surface, data, 'png')
        return data.getvalue()

    def known(self, name: str) -> bool:
        """Whether pygame has a key of that name (pygame.key.key_code)."""
        try:
            self.pygame.key.key_code(name)
        except ValueError:
            return False
        return True

    def mods(self) -> int:
        """The KMOD_ bits of the shift, ctrl and alt keys held through the seam."""
        pygame = self.pygame
        bits = {pygame.K_LSHIFT: pygame.KMOD_LSHIFT, pygame.K_RSHIFT: pygame.KMOD_RSHIFT,
                pygame.K_LCTRL: pygame.KMOD_LCTRL, pygame.K_RCTRL: pygame.KMOD_RCTRL,
                pygame.K_LALT: pygame.KMOD_LALT, pygame.K_RALT: pygame.KMOD_RALT}
        mods = 0
        for held in self.held:
            mods |= bits.get(held, 0)
        return mods

    def inject(self) -> None:
        """Post the seam's new key events as KEYDOWN/KEYUP and keep the held keys for get_pressed."""
        self.seam.flush_due()
        pygame = self.pygame
        for down, name in self.seam.key_events(self.known):
            code = pygame.key.key_code(name)
            if down:
                self.held.add(code)
            else:
                self.held.discard(code)
            mods = self.mods()
            text = name if len(name) == 1 else {'space': ' ', 'return': '\r', 'tab': '\t'}.get(name, '')
            if mods & pygame.KMOD_SHIFT:
                text = text.upper()
            # SDL keycodes of keys without a character are their scancode with bit 30 set.
            scancode = code & ~(1 << 30) if code & (1 << 30) else 0
            attributes: dict[str, object] = {'key': code, 'mod': mods, 'scancode': scancode, 'window': None}
            if down:
                attributes['unicode'] = text
            pygame.event.post(pygame.event.Event(pygame.KEYDOWN if down else pygame.KEYUP, attributes))


def main() -> None:
    """For bootstrap.sh: print the fallback notice if this machine falls back, nothing if it does not."""
    problem = gui_build_problem()
    if problem is not None:
        print(notice(problem))


if __name__ == '__main__':
    main()
