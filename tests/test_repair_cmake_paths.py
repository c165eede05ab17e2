"""scripts/repair_cmake_paths.py: the wheels' CMake exports name this venv, and uv's cache is left alone."""

import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import setup_scripts

SCRIPT = setup_scripts.SCRIPTS / 'repair_cmake_paths.py'
repair = setup_scripts.load('repair_cmake_paths')

OURS_INCLUDE = '/home/student/.pyenv/versions/3.11.7/include/python3.11'
OURS_SITE = '/home/student/owl-kit-lab/.venv/lib/python3.11/site-packages'
EXPORT_LINE = '  INTERFACE_INCLUDE_DIRECTORIES "{include};{site}/numpy/_core/include"\n'
RELATIVE_LINE = ('set(_generator "${rosidl_generator_py_DIR}/../../../lib/python3.11/site-packages/'
                 'rosidl_generator_py/__init__.py")\n')
WHEEL_TEXT = EXPORT_LINE.format(include='/opt/python/cp311-cp311/include/python3.11',
                                site='/opt/python/cp311-cp311/lib/python3.11/site-packages') + RELATIVE_LINE
REPAIRED_TEXT = EXPORT_LINE.format(include=OURS_INCLUDE, site=OURS_SITE) + RELATIVE_LINE


def export_file(folder: Path, text: str) -> Path:
    path = folder / 'share' / 'std_msgs' / 'cmake' / 'export_std_msgs__rosidl_generator_pyExport.cmake'
    path.parent.mkdir(parents=True)
    path.write_text(text)
    return path


def test_the_build_machines_paths_become_this_venvs_and_a_second_run_changes_nothing(tmp_path):
    path = export_file(tmp_path, WHEEL_TEXT)
    assert repair.repair_tree(tmp_path / 'share', OURS_INCLUDE, OURS_SITE) == [path]
    assert path.read_text() == REPAIRED_TEXT
    assert repair.repair_tree(tmp_path / 'share', OURS_INCLUDE, OURS_SITE) == []


def test_a_file_hard_linked_from_uvs_cache_is_replaced_and_the_cache_keeps_the_wheels_text(tmp_path):
    # uv links a wheel's files into the venv; a write through the link gave the next venv this one's paths.
    cached = tmp_path / 'cache' / 'export.cmake'
    cached.parent.mkdir()
    cached.write_text(WHEEL_TEXT)
    cached.chmod(0o644)
    installed = tmp_path / 'venv' / 'share' / 'std_msgs' / 'cmake' / 'export.cmake'
    installed.parent.mkdir(parents=True)
    os.link(cached, installed)
    assert repair.repair_tree(tmp_path / 'venv' / 'share', OURS_INCLUDE, OURS_SITE) == [installed]
    assert installed.read_text() == REPAIRED_TEXT
    assert cached.read_text() == WHEEL_TEXT
    assert cached.stat().st_nlink == 1
    assert installed.stat().st_mode & 0o777 == 0o644
    assert [p.name for p in installed.parent.iterdir()] == ['export.cmake']


def test_a_file_an_earlier_venv_was_written_into_is_pointed_at_this_one(tmp_path):
    # What the old bootstrap left in uv's cache: another clone's venv, since deleted.
    earlier = EXPORT_LINE.format(include='/usr/include/python3.11',
                                 site='/tmp/first-clone/.venv/lib/python3.11/site-packages') + RELATIVE_LINE
    path = export_file(tmp_path, earlier)
    assert repair.repair_tree(tmp_path / 'share', OURS_INCLUDE, OURS_SITE) == [path]
    assert path.read_text() == REPAIRED_TEXT


def test_outside_a_venv_it_stops_with_one_line_and_changes_nothing():
    system_python = Path(sys.base_prefix) / 'bin' / f'python{sys.version_info.major}.{sys.version_info.minor}'
    result = subprocess.run([str(system_python), str(SCRIPT)], capture_output=True, text=True, timeout=60,
                            env={**os.environ, '_ROS_WHEELS_BOOTSTRAP_COMPLETE': '1'})
    assert result.returncode == 2
    assert result.stdout == ''
    assert result.stderr == "repair_cmake_paths: run this with the venv's python, not the system one\n"


def test_this_venvs_exports_name_its_own_numpy_headers():
    exports = sorted((Path(sys.prefix) / 'share').glob('*/cmake/export_*__rosidl_generator_pyExport.cmake'))
    assert exports, 'the venv has no Python interface exports'
    numpy_include = f"{sysconfig.get_paths()['purelib']}/numpy/_core/include"
    assert Path(numpy_include).is_dir()
    for path in exports:
        text = path.read_text()
        assert '/opt/python/' not in text, path
        assert numpy_include in text, path
