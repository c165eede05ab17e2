"""Run ruff on a list of files and read back what it found.

ament_flake8 and ament_pep257 check the rules of flake8 and pydocstyle with ruff, which implements
them and is pinned in the project's requirements, rather than installing flake8 and its plugins.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from dataclasses import dataclass

from ament_lint.source_files import LintInputError

# ruff names the problems that are not rule violations; flake8's codes for them.
FLAKE8_CODES = {'invalid-syntax': 'E999', 'io-error': 'E902', None: 'E999'}


@dataclass(frozen=True)
class Finding:
    """One problem in one file, printed as flake8 prints it: path:line:column: CODE message."""

    path: str
    line: int
    column: int
    code: str
    message: str

    def __str__(self) -> str:
        return f'{self.path}:{self.line}:{self.column}: {self.code} {self.message}'


def run_ruff(files: list[str], options: list[str]) -> list[Finding]:
    """The findings of `ruff check` with these options on these files, sorted by file and position.

    Only the options given apply (--isolated), so a ruff configuration of the user's own does not
    change what ament's rules are. LintInputError when ruff is missing or refuses the options.
    """
    if not files:
        return []
    command = [sys.executable, '-m', 'ruff', 'check', '--isolated', '--no-cache', '--exit-zero',
               '--output-format', 'json', *options, '--', *files]
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        if 'No module named ruff' in result.stderr:
            raise LintInputError('ruff is not installed in this Python: pip install ruff '
                                 '(requirements.txt pins its version)')
        reason = next((line for line in result.stderr.splitlines() if line.strip()), 'no output')
        raise LintInputError(f'ruff failed (exit {result.returncode}): {reason}')
    # ruff names files by absolute path; report them as the caller named them.
    given = {os.path.abspath(path): path for path in files}
    findings = [
        Finding(path=given.get(item['filename'], item['filename']), line=item['location']['row'],
                column=item['location']['column'], code=FLAKE8_CODES.get(item['code'], item['code']),
                message=item['message'])
        for item in json.loads(result.stdout or '[]')]
    order = {path: index for index, path in enumerate(files)}
    return sorted(findings, key=lambda f: (order.get(f.path, len(order)), f.line, f.column, f.code))
