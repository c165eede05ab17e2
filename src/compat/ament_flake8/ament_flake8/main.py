"""`ament_flake8`: ament's flake8 configuration, checked with ruff.

Upstream runs flake8 with pycodestyle, pyflakes and the builtins, comprehensions, docstrings,
import-order and quotes plugins. ruff implements those rules under the same codes; each maps here:

- pycodestyle (E, W) and pyflakes (F): all of them, lines up to 99 characters, except what flake8
  leaves out by default (E121/E123/E126/E226/E24/E704/W503/W504). ruff has the whitespace and
  blank-line rules (E1, E2, E3) only in preview, so those are named one by one with preview on.
- flake8-quotes (Q): single quotes for strings, double for docstrings and multi-line strings.
- flake8-builtins (A001-A003) and flake8-comprehensions (C4): as those plugins have them.
- flake8-docstrings (D): the pep257 convention without D100-D107, as ament's configuration says.
- flake8-import-order (I100-I202, google style) is not checked: ruff's isort rule also demands its
  own layout (no blank line inside a group, its way of wrapping), which would fail code that
  ament_flake8 accepts, the ROS 2 tutorials' own listings among it.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections import Counter

from ament_lint.ruff_check import Finding, run_ruff
from ament_lint.source_files import LintInputError, find_files

MAX_LINE_LENGTH = 99
# pycodestyle's rules that ruff offers only in preview, minus flake8's default ignores.
PYCODESTYLE_PREVIEW_RULES = (
    'E111', 'E112', 'E113', 'E114', 'E115', 'E116', 'E117',
    'E201', 'E202', 'E203', 'E204', 'E211', 'E221', 'E222', 'E223', 'E224', 'E225', 'E227', 'E228',
    'E231', 'E251', 'E252', 'E261', 'E262', 'E265', 'E266', 'E271', 'E272', 'E273', 'E274', 'E275',
    'E301', 'E302', 'E303', 'E304', 'E305', 'E306', 'E502', 'W391',
)
SELECTED_RULES = ('E', 'W', 'F', 'Q', 'A001', 'A002', 'A003', 'C4', 'D', *PYCODESTYLE_PREVIEW_RULES)
# ament_flake8.ini's docstring ignores; D203/D212/D404 are outside the pep257 convention already.
IGNORED_RULES = ('D100', 'D101', 'D102', 'D103', 'D104', 'D105', 'D106', 'D107')


def ruff_options(max_line_length: int) -> list[str]:
    """The `ruff check` options that make up ament_flake8's configuration."""
    return [
        '--preview', '--config', 'lint.explicit-preview-rules = true',
        '--select', ','.join(SELECTED_RULES), '--ignore', ','.join(IGNORED_RULES),
        '--line-length', str(max_line_length),
        '--config', "lint.flake8-quotes.inline-quotes = 'single'",
        '--config', "lint.pydocstyle.convention = 'pep257'",
    ]


def parse_arguments(argv: list[str] | None) -> argparse.Namespace:
    """The command line, checked by argparse (a usage error exits 2)."""
    parser = argparse.ArgumentParser(
        prog='ament_flake8', description="Check Python code against ament's flake8 rules (with ruff).",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument('paths', nargs='*', default=[os.curdir],
                        help="Files or folders to check; in folders, files ending in '.py'.")
    parser.add_argument('--linelength', metavar='N', type=int, default=MAX_LINE_LENGTH,
                        help='The maximum line length.')
    parser.add_argument('--exclude', metavar='filename', nargs='*', default=[], dest='excludes',
                        help='Files or folders to leave out, by path or name pattern.')
    args = parser.parse_args(argv)
    if args.linelength < 1:
        parser.error(f'--linelength must be a positive number of characters, not {args.linelength}')
    return args


def main(argv: list[str] | None = None) -> int:
    """Run the check and print its report; 0 when nothing is found, 1 otherwise."""
    rc, _ = main_with_errors(argv)
    return rc


def main_with_errors(argv: list[str] | None = None) -> tuple[int, list[str]]:
    """Run the check and print its report; (0 or 1, one 'path:line:column: CODE message' per problem).

    `argv` defaults to the command line's arguments; with no paths the current folder is checked.
    """
    args = parse_arguments(argv)
    try:
        files = find_files(args.paths, ('.py',), args.excludes)
        findings = run_ruff(files, ruff_options(args.linelength))
    except LintInputError as error:
        print(f'ament_flake8: {error}', file=sys.stderr)
        return 1, [str(error)]
    print_report(files, findings)
    return (1 if findings else 0), [str(finding) for finding in findings]


def print_report(files: list[str], findings: list[Finding]) -> None:
    """Each problem, then the counts and the files checked, laid out as upstream's report."""
    for finding in findings:
        print()
        print(finding)
    print()
    print(f'{len(files)} files checked')
    if not findings:
        print('No problems found')
    else:
        print(f'{len(findings)} errors')
        print()
        for kind, count in sorted(Counter(finding.code[0] for finding in findings).items()):
            print(f"'{kind}'-type errors: {count}")
    print()
    print('Checked files:')
    print(''.join(f'\n* {path}' for path in files))


if __name__ == '__main__':
    sys.exit(main())
