"""The repository stays ruff clean, mypy clean (rules in pyproject.toml), free of conflict markers."""

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_ruff_finds_nothing():
    result = subprocess.run([sys.executable, '-m', 'ruff', 'check', '--no-cache', str(ROOT)],
                            capture_output=True, text=True, cwd=ROOT)
    assert result.returncode == 0, result.stdout + result.stderr


# The second mypy run: tests, scripts, benchmarks and docs' scripts have their bodies checked, but a
# test need not annotate its fixtures; our packages are read from the installed workspace. It keeps a
# cache of its own: the two runs differ in options and in where our packages come from (src or the
# workspace's links), and go side by side in two workers; in one cache each run would redo or take
# the other's entries.
MYPY_OUTSIDE_SRC = ('--allow-untyped-defs', '--allow-incomplete-defs', '--follow-untyped-imports',
                    '--cache-dir', 'build/mypy_cache_outside_src', 'tests', 'scripts', 'bench', 'docs')


@pytest.mark.parametrize('arguments', [(), MYPY_OUTSIDE_SRC], ids=['src', 'tests-scripts-bench-docs'])
def test_mypy_finds_nothing(arguments):
    # With the settings of pyproject.toml; its cache (build/mypy_cache) makes a re-run with few
    # changes take a few seconds.
    result = subprocess.run([sys.executable, '-m', 'mypy', *arguments], capture_output=True, text=True,
                            cwd=ROOT)
    assert result.returncode == 0, result.stdout + result.stderr



CONFLICT_MARKERS = ('<<<<<<< ', '>>>>>>> ', '||||||| ')


def unresolved_conflicts(paths: list[Path]) -> list[str]:
    """'file:line' for each line that opens, splits or closes a merge conflict left in a file."""
    found = []
    for path in paths:
        try:
            lines = path.read_text(encoding='utf-8').splitlines()
        except (UnicodeDecodeError, IsADirectoryError, FileNotFoundError):
            continue  # binary files (pictures) cannot hold text markers
        found += [f'{path}:{number}' for number, line in enumerate(lines, 1)
                  if line.startswith(CONFLICT_MARKERS) or line == '=======']
    return found


def test_no_tracked_file_holds_merge_conflict_markers():
    listed = subprocess.run(['git', 'ls-files', '-z'], cwd=ROOT, capture_output=True, text=True, check=True)
    paths = [ROOT / name for name in listed.stdout.split('\0') if name]
    assert len(paths) > 100
    assert unresolved_conflicts(paths) == []


def test_a_conflict_left_in_a_file_is_found(tmp_path: Path):
    left = tmp_path / 'README.md'
    left.write_text('| a |\n<<<<<<< HEAD\n| b |\n=======\n| c |\n>>>>>>> other\n')
    heading = tmp_path / 'guide.md'
    heading.write_text('Title\n=====\n')
    assert unresolved_conflicts([left, heading]) == [f'{left}:2', f'{left}:4', f'{left}:6']
