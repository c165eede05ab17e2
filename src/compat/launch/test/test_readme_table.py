"""The README's table of upstream's public names says what the code does.

Each row names a module, a name and a status: a name that 'works' or 'refuses' is there to import
(a refusal is one line when used, tested with the feature); a 'missing' one is not. The summary line
counts the rows.
"""

import importlib
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parent.parent / 'README.md'
ROW = re.compile(r'^\| `([\w.]+)` \| `(\w+)` \| (works|refuses|missing)\b(.*) \|$', re.MULTILINE)
SUMMARY = re.compile(r'\((\d+) names in (\d+) modules\).*\*\*(\d+) work, (\d+) refuse with a reason, (\d+) '
                     r'missing\*\*', re.DOTALL)
ROWS = ROW.findall(README.read_text())


def test_the_table_has_a_row_for_each_name_once():
    assert len(ROWS) > 200
    keys = [(module, name) for module, name, _, _ in ROWS]
    assert len(keys) == len(set(keys))


def test_the_summary_counts_the_rows():
    names, modules, works, refuses, missing = map(int, SUMMARY.search(README.read_text()).groups())
    statuses = [status for _, _, status, _ in ROWS]
    assert (names, modules) == (len(ROWS), len({module for module, _, _, _ in ROWS}))
    assert (works, refuses, missing) == (statuses.count('works'), statuses.count('refuses'),
                                         statuses.count('missing'))


@pytest.mark.parametrize(('module', 'name', 'status', 'note'), ROWS, ids=[f'{m}.{n}' for m, n, _, _ in ROWS])
def test_each_row_matches_the_code(module, name, status, note):
    present = hasattr(importlib.import_module(module), name)
    if status == 'missing':
        assert not present, f'{module}.{name} exists: its row should say how it works'
        assert note.startswith(':'), 'a missing name says why'
    else:
        assert present, f'{module}.{name} is not there, yet its row says it {status}'
