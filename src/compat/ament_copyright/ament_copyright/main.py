"""`ament_copyright`: every non-empty source file starts with a copyright notice and a known license.

The header is the first comment block of a file (after a shebang or coding line). It must hold a
`Copyright <year> <holder>` line and the text (or the SPDX identifier) of one of the licenses that
`ros2 pkg create` knows.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
from dataclasses import dataclass

from ament_lint.source_files import LintInputError, find_files

SOURCE_SUFFIXES = ('.c', '.cc', '.cpp', '.cxx', '.h', '.hh', '.hpp', '.hxx', '.cmake', '.py')
COPYRIGHT_NOTICE = re.compile(r'^Copyright\s+(?:\([cC]\)\s+)?\d{4}(?:\s*[-,]\s*\d{4})*,?\s+\S.*$',
                              re.MULTILINE)
SPDX_IDENTIFIER = re.compile(r'SPDX-License-Identifier:\s*(\S+)')
COMMENT_START = re.compile(r'^\s*(?:#|//|/\*+|\*/|\*)\s?')
UNKNOWN_LICENSE = '<unknown>'


@dataclass(frozen=True)
class License:
    """A license a header can carry: its SPDX identifier and phrases only its header text has."""

    spdx: str
    phrases: tuple[str, ...]
    unless: tuple[str, ...] = ()

    def matches(self, text: str) -> bool:
        """Whether a header's text (whitespace collapsed) states this license."""
        return all(p in text for p in self.phrases) and not any(p in text for p in self.unless)


# Most specific first: BSD-3-Clause's text contains BSD-2-Clause's, MIT's contains MIT-0's.
LICENSES = (
    License('Apache-2.0', ('Licensed under the Apache License, Version 2.0',)),
    License('BSL-1.0', ('Boost Software License - Version 1.0',)),
    License('BSD-3-Clause', ('Redistribution and use in source and binary forms', 'Neither the name')),
    License('BSD-2-Clause', ('Redistribution and use in source and binary forms',)),
    License('MIT', ('Permission is hereby granted, free of charge',
                    'The above copyright notice and this permission notice shall be included')),
    License('MIT-0', ('Permission is hereby granted, free of charge',)),
    License('LGPL-3.0-only', ('GNU Lesser General Public License', 'version 3')),
    License('GPL-3.0-only', ('GNU General Public License', 'version 3'), unless=('Lesser',)),
)


def header_text(source: str) -> str:
    """The first comment block's text, comment markers removed, after a shebang or coding line."""
    lines = source.splitlines()
    while lines and (lines[0].startswith('#!') or re.match(r'^#.*coding[:=]', lines[0])
                     or not lines[0].strip()):
        lines.pop(0)
    header = []
    for line in lines:
        if not line.strip():
            header.append('')
            continue
        marker = COMMENT_START.match(line)
        if not marker:
            break
        header.append(line[marker.end():].rstrip().removesuffix('*/').rstrip())
    return '\n'.join(header)


def license_of(header: str) -> str:
    """The SPDX identifier of the license the header states, or UNKNOWN_LICENSE."""
    spdx = SPDX_IDENTIFIER.search(header)
    if spdx:
        return spdx.group(1)
    flat = ' '.join(header.split())
    return next((known.spdx for known in LICENSES if known.matches(flat)), UNKNOWN_LICENSE)


def check_file(path: str) -> tuple[bool, str]:
    """(whether the file passes, what was found in it)."""
    with open(path, encoding='utf-8', errors='replace') as f:
        source = f.read()
    if not source.strip():
        return True, 'file empty'
    header = header_text(source)
    notices = [match.group(0) for match in COPYRIGHT_NOTICE.finditer(header)]
    if not notices:
        return False, 'could not find copyright notice'
    license_name = license_of(header)
    return license_name != UNKNOWN_LICENSE, f'copyright={", ".join(notices)}, license={license_name}'


def is_package_setup_py(path: str) -> bool:
    """setup.py beside a package.xml: ROS packages' boilerplate, which upstream does not check."""
    return os.path.basename(path) == 'setup.py' and os.path.isfile(
        os.path.join(os.path.dirname(path), 'package.xml'))


def parse_arguments(argv: list[str] | None) -> argparse.Namespace:
    """The command line, checked by argparse (a usage error exits 2)."""
    parser = argparse.ArgumentParser(
        prog='ament_copyright', description='Check source files for a copyright notice and license.',
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument('paths', nargs='*', default=[os.curdir],
                        help=f'Files or folders to check; in folders, files ending in '
                             f'{", ".join(SOURCE_SUFFIXES)} (but a package\'s setup.py).')
    parser.add_argument('--exclude', metavar='filename', nargs='*', default=[], dest='excludes',
                        help='Files or folders to leave out, by path or name pattern.')
    parser.add_argument('--verbose', action='store_true', help='Report every file, not only failing ones.')
    parser.add_argument('--list-licenses', action='store_true', help='List the licenses a header may state.')
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    """Check the files and print each failing one; 0 when all pass, 1 otherwise.

    `argv` defaults to the command line's arguments; with no paths the current folder is checked.
    """
    args = parse_arguments(argv)
    if args.list_licenses:
        for known in LICENSES:
            print(known.spdx)
        return 0
    try:
        files = [path for path in find_files(args.paths, SOURCE_SUFFIXES, args.excludes)
                 if not is_package_setup_py(path)]
    except LintInputError as error:
        print(f'ament_copyright: {error}', file=sys.stderr)
        return 1
    failures = 0
    for path in files:
        passed, found = check_file(path)
        failures += not passed
        if args.verbose or not passed:
            print(f'{path}: {found}', file=sys.stdout if passed else sys.stderr)
    if failures:
        print(f'{failures} errors, checked {len(files)} files', file=sys.stderr)
        return 1
    print(f'No problems found, checked {len(files)} files')
    return 0


if __name__ == '__main__':
    sys.exit(main())
