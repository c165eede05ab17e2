"""Ruff and mypy clean (rules in pyproject.toml), no conflict markers, commit subjects of 72 at most."""

import itertools
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from gates import prerequisite_missing

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


# Commit subjects: at most 72 characters (aim for 50), from this date on; earlier ones are history.
COMMIT_HOOK = ROOT / 'scripts' / 'git-hooks' / 'commit-msg'
SUBJECT_LIMIT = 72
SUBJECT_RULE_SINCE = '2026-12-03T12:00:00+00:00'


def git(*arguments: str) -> subprocess.CompletedProcess:
    return subprocess.run(['git', '-C', str(ROOT), *arguments], capture_output=True, text=True)


def test_commit_subjects_since_the_rule_are_at_most_72_characters():
    listed = git('log', f'--since={SUBJECT_RULE_SINCE}', '--format=%h %s')
    if listed.returncode != 0:
        prerequisite_missing(f'no git history here: {listed.stderr.strip()}')
    long = [line for line in listed.stdout.splitlines() if len(line.split(' ', 1)[1]) > SUBJECT_LIMIT]
    assert not long, long


@pytest.mark.parametrize(('message', 'accepted'), [
    ('x' * 72 + '\n\nA body line may be as long as it likes, ' + 'y' * 80 + '\n', True),
    ('# a comment of git, longer than the limit: ' + 'z' * 80 + '\n\n' + 'x' * 50 + '\n', True),
    ('x' * 73 + '\n', False),
    ('\n\n' + 'é' * 73 + '\n', False),
], ids=['72', 'comments-skipped', '73', 'after-blank-lines'])
def test_the_commit_msg_hook_refuses_a_subject_over_72_characters_in_one_line(tmp_path: Path, message: str,
                                                                               accepted: bool):
    (tmp_path / 'COMMIT_EDITMSG').write_text(message)
    result = subprocess.run([str(COMMIT_HOOK), str(tmp_path / 'COMMIT_EDITMSG')], capture_output=True,
                            text=True)
    assert (result.returncode == 0) == accepted, result.stderr
    if not accepted:
        [line] = result.stderr.splitlines()
        assert line.startswith('commit-msg: the subject has 73 characters, at most 72'), line
    assert (tmp_path / 'COMMIT_EDITMSG').read_text() == message  # the message is kept


def test_setup_installed_the_commit_msg_hook():
    hooks = git('rev-parse', '--path-format=absolute', '--git-path', 'hooks')
    if hooks.returncode != 0:
        prerequisite_missing(f'not a git checkout: {hooks.stderr.strip()}')
    installed = Path(hooks.stdout.strip()) / 'commit-msg'
    assert installed.read_bytes() == COMMIT_HOOK.read_bytes()
    assert os.access(installed, os.X_OK)


# A new reader's path: the README, CONTRIBUTING.md, the architecture; no relative link there, in docs/
# or in a package's README leads nowhere.
READERS_PATH = ('README.md', 'CONTRIBUTING.md', 'docs/architecture.md')
MARKDOWN_LINK = re.compile(r'\]\(([^)\s]+)\)')


def dead_links(document: Path) -> list[str]:
    """The relative links of a Markdown document whose file is missing (web addresses and anchors aside)."""
    dead = []
    for target in MARKDOWN_LINK.findall(document.read_text()):
        if re.match(r'[a-z]+:', target) or target.startswith('#'):
            continue
        if not (document.parent / target.split('#', 1)[0]).exists():
            dead.append(target)
    return dead


def test_the_readers_path_links_on_and_has_no_dead_link():
    for earlier, later in itertools.pairwise(READERS_PATH):
        assert later.rsplit('/', 1)[-1] in (ROOT / earlier).read_text(), (earlier, later)
    documents = [ROOT / name for name in READERS_PATH] + sorted((ROOT / 'docs').rglob('*.md'))
    documents += sorted((ROOT / 'src').glob('*/**/README.md'))
    for document in documents:
        assert dead_links(document) == [], document


def test_a_dead_link_is_found(tmp_path: Path):
    (tmp_path / 'there.md').write_text('')
    (tmp_path / 'a.md').write_text('[ok](there.md) [web](https://ros.org) [gone](docs/gone.md#x) [top](#a)')
    assert dead_links(tmp_path / 'a.md') == ['docs/gone.md#x']
