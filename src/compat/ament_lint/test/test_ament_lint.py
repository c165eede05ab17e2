"""ament_lint: the file search every linter shares, the ruff runner, and the `linter` marker."""

import subprocess
import sys

import pytest
from ament_lint.ruff_check import run_ruff
from ament_lint.source_files import LintInputError, find_files


def make(root, *paths):
    for path in paths:
        (root / path).parent.mkdir(parents=True, exist_ok=True)
        (root / path).write_text('x = 1\n')


def test_folders_are_searched_as_upstream_skipping_hidden_private_and_ignored_ones(tmp_path, monkeypatch):
    make(tmp_path, 'a.py', 'pkg/b.py', 'pkg/c.txt', '.hidden/d.py', '_private/e.py', 'skipped/f.py',
         'skipped/AMENT_IGNORE', 'build_dir/g.py')
    monkeypatch.chdir(tmp_path)
    assert find_files(['.'], ('.py',), excludes=['build_dir']) == ['a.py', 'pkg/b.py']


def test_a_file_named_directly_is_checked_once_whatever_its_name(tmp_path, monkeypatch):
    make(tmp_path, 'script', 'pkg/b.py')
    monkeypatch.chdir(tmp_path)
    assert find_files(['script', 'pkg', 'pkg/b.py'], ('.py',)) == ['script', 'pkg/b.py']


def test_a_missing_path_is_an_error_not_an_empty_check(tmp_path):
    with pytest.raises(LintInputError, match='no_such_dir: no such file or directory'):
        find_files([str(tmp_path / 'no_such_dir')], ('.py',))


def test_ruff_findings_keep_the_callers_paths_and_syntax_errors_are_e999(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / 'unused.py').write_text('import os\n')
    (tmp_path / 'broken.py').write_text('def f(:\n')
    findings = run_ruff(['unused.py', 'broken.py'], ['--select', 'F'])
    unused = [str(f) for f in findings if f.path == 'unused.py']
    assert unused == ['unused.py:1:8: F401 `os` imported but unused']
    assert {f.code for f in findings if f.path == 'broken.py'} == {'E999'}
    assert run_ruff([], ['--select', 'F']) == []


def test_options_ruff_refuses_are_a_clear_error(tmp_path):
    (tmp_path / 'a.py').write_text('x = 1\n')
    with pytest.raises(LintInputError, match='ruff failed'):
        run_ruff([str(tmp_path / 'a.py')], ['--select', 'NOT_A_RULE'])


def test_the_linter_marker_is_registered_with_pytest(tmp_path):
    # In an empty folder, as a created package's tests run: from the repository this pytest would
    # also load tests/conftest.py, whose start clears the running suite's rerun reports.
    markers = subprocess.run([sys.executable, '-m', 'pytest', '--markers', '-p', 'no:cacheprovider'],
                             cwd=tmp_path, capture_output=True, text=True, check=True).stdout
    for marker in ('linter', 'flake8', 'pep257', 'copyright'):
        assert f'@pytest.mark.{marker}:' in markers
