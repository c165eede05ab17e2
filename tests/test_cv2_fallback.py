"""`import cv2`: OpenCV's GUI build where its system libraries load, else its headless build.

A machine without libGL is simulated by an empty libGL.so.1 first on LD_LIBRARY_PATH: the GUI
build's native module then fails to load exactly as it does where the library is missing.
OWL_HEADLESS=0 stands for a display (the fallback says so in one line), OWL_HEADLESS=1 for none
(silent: the first window says there is no display; tests/test_headless_windows.py).
"""

import ctypes
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
VENV = Path(sys.prefix)
HEADLESS = VENV / 'opencv-headless'
PINNED = next(line.split('==')[1] for line in (ROOT / 'requirements.txt').read_text().splitlines()
              if line.startswith('opencv-python=='))
REPORT = ('import sys, cv2, numpy; ok, _ = cv2.imencode(".png", numpy.zeros((2, 2), numpy.uint8)); '
          'print(cv2.version.opencv_version, cv2.version.headless, cv2.__file__, ok, '
          f'{str(HEADLESS)!r} in sys.path)')
APT = "for windows: 'sudo apt install libgl1 libglib2.0-0'"


def python(*args: str, broken_libgl: Path | None = None, display: bool = True) -> subprocess.CompletedProcess:
    env = dict(os.environ, OWL_HEADLESS='0' if display else '1')
    if broken_libgl is not None:
        broken_libgl.mkdir()
        (broken_libgl / 'libGL.so.1').write_bytes(b'')
        paths = [str(broken_libgl), env.get('LD_LIBRARY_PATH')]
        env['LD_LIBRARY_PATH'] = os.pathsep.join(filter(None, paths))
    return subprocess.run([sys.executable, *args], env=env, capture_output=True, text=True, timeout=120)


def desktop_libraries_load() -> bool:
    try:
        for library in ('libGL.so.1', 'libgthread-2.0.so.0'):
            ctypes.CDLL(library)
    except OSError:
        return False
    return True


def test_setup_installed_the_headless_build_of_the_pinned_version():
    assert (HEADLESS / 'cv2' / '__init__.py').is_file()
    assert (HEADLESS / f'opencv_python_headless-{PINNED}.dist-info').is_dir()
    assert not list(HEADLESS.glob('numpy*')), 'the headless folder must not shadow the pinned numpy'


def test_without_libgl_cv2_is_the_headless_build_with_one_line_saying_so(tmp_path):
    result = python('-c', REPORT, broken_libgl=tmp_path / 'lib')
    assert result.returncode == 0, result.stderr
    assert 'Traceback' not in result.stderr
    version, headless, path, encoded, on_path = result.stdout.split()
    assert (version, headless, encoded, on_path) == (PINNED, 'True', 'True', 'True')
    assert Path(path).is_relative_to(HEADLESS)
    [line] = result.stderr.splitlines()
    assert line.startswith("cv2: OpenCV's GUI build cannot load here (")
    assert 'libGL.so.1' in line
    assert line.endswith(APT)


def test_without_libgl_and_without_a_display_the_fallback_is_silent(tmp_path):
    result = python('-c', REPORT, broken_libgl=tmp_path / 'lib', display=False)
    assert result.returncode == 0, result.stderr
    version, headless, path, encoded, on_path = result.stdout.split()
    assert (version, headless, encoded, on_path) == (PINNED, 'True', 'True', 'True')
    assert Path(path).is_relative_to(HEADLESS)
    assert result.stderr == ''


@pytest.mark.skipif(not desktop_libraries_load(), reason='this machine lacks libGL or glib: it falls back')
def test_with_the_libraries_cv2_is_the_gui_build_untouched():
    result = python('-c', REPORT)
    assert result.returncode == 0, result.stderr
    version, headless, path, encoded, on_path = result.stdout.split()
    assert (version, headless, encoded, on_path) == (PINNED, 'False', 'True', 'False')
    assert not Path(path).is_relative_to(HEADLESS)
    assert result.stderr == ''


def test_the_setup_check_prints_the_notice_only_when_falling_back(tmp_path):
    falling_back = python('-m', 'owl_gui_hook', broken_libgl=tmp_path / 'lib')
    assert falling_back.returncode == 0
    [line] = falling_back.stdout.splitlines()
    assert line.startswith("OpenCV's GUI build cannot load here (")
    assert line.endswith(APT)
    if desktop_libraries_load():
        assert python('-m', 'owl_gui_hook').stdout == ''
