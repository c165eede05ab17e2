"""`ament_pep257`: pydocstyle's docstring checks as ament configures them, run with ruff's D rules.

ruff implements pydocstyle's rules under the same codes (D100-D419). The default, the "ament"
convention, checks every one of them except D100-D107 (missing docstrings), D203, D212 and D404,
so a multi-line docstring's summary starts on its second line (D213), as in ROS 2's own code.
"""

from __future__ import annotations

import argparse
import os
import sys

from ament_lint.ruff_check import run_ruff
from ament_lint.source_files import LintInputError, find_files

AMENT_CONVENTION = 'ament'
# ruff's conventions are pydocstyle's.
PYDOCSTYLE_CONVENTIONS = ('pep257', 'numpy', 'google')
AMENT_IGNORED_RULES = ('D100', 'D101', 'D102', 'D103', 'D104', 'D105', 'D106', 'D107',
                       'D203', 'D212', 'D404')


def parse_arguments(argv: list[str] | None) -> argparse.Namespace:
    """The command line, checked by argparse (a usage error exits 2)."""
    parser = argparse.ArgumentParser(
        prog='ament_pep257', description='Check docstrings against PEP 257 (with ruff).',
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    rule_set = parser.add_mutually_exclusive_group()
    rule_set.add_argument('--ignore', nargs='+', default=[],
                          help='Check every docstring rule but these codes.')
    rule_set.add_argument('--select', nargs='+', default=[], help='Check only these codes.')
    rule_set.add_argument('--convention', choices=(AMENT_CONVENTION, *PYDOCSTYLE_CONVENTIONS),
                          default=AMENT_CONVENTION,
                          help=f'A preset rule set; "{AMENT_CONVENTION}" is every rule but '
                               f'{", ".join(AMENT_IGNORED_RULES)}.')
    parser.add_argument('--add-ignore', nargs='+', default=[], help='Codes to leave out as well.')
    parser.add_argument('--add-select', nargs='+', default=[], help='Codes to check as well.')
    parser.add_argument('paths', nargs='*', default=[os.curdir],
                        help="Files or folders to check; in folders, files ending in '.py'.")
    parser.add_argument('--exclude', metavar='filename', nargs='*', default=[], dest='excludes',
                        help='Files or folders to leave out, by path or name pattern.')
    return parser.parse_args(argv)


def ruff_options(args: argparse.Namespace) -> list[str]:
    """The `ruff check` options for the rule set the arguments ask for."""
    select = list(args.select) or ['D']
    ignore = list(args.ignore)
    options = []
    if not (args.select or args.ignore):
        if args.convention == AMENT_CONVENTION:
            ignore = list(AMENT_IGNORED_RULES)
        else:
            options = ['--config', f"lint.pydocstyle.convention = '{args.convention}'"]
    select += args.add_select
    ignore += args.add_ignore
    return [*options, '--select', ','.join(select), *(['--ignore', ','.join(ignore)] if ignore else [])]


def main(argv: list[str] | None = None) -> int:
    """Check the docstrings and print what is wrong; 0 when nothing is, 1 otherwise.

    `argv` defaults to the command line's arguments; with no paths the current folder is checked.
    """
    args = parse_arguments(argv)
    for code in (*args.select, *args.ignore, *args.add_select, *args.add_ignore):
        if not code.startswith('D'):
            print(f"ament_pep257: '{code}' is not a docstring rule (codes start with D)", file=sys.stderr)
            return 1
    try:
        files = find_files(args.paths, ('.py',), args.excludes)
        findings = run_ruff(files, ruff_options(args))
    except LintInputError as error:
        print(f'ament_pep257: {error}', file=sys.stderr)
        return 1
    for path in files:
        print('checking', path)
    for finding in findings:
        print(f'{finding.path}:{finding.line} {finding.code}: {finding.message}', file=sys.stderr)
    if findings:
        print(f'{len(findings)} errors', file=sys.stderr)
        return 1
    print('No problems found')
    return 0


if __name__ == '__main__':
    sys.exit(main())
