"""ament_copyright: copyright notices and license headers, which files are checked, and errors."""

import pytest
from ament_copyright.main import header_text, license_of, main

APACHE_PY = '''#!/usr/bin/env python3
# Copyright 2024 Ann Example
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.

print('hi')
'''
SPDX_CPP = '''// Copyright (c) 2023-2024, Owl Kit Lab
// SPDX-License-Identifier: BSD-3-Clause

int main() { return 0; }
'''
MIT_BLOCK = '''/*
 * Copyright 2024 Ann
 *
 * Permission is hereby granted, free of charge, to any person obtaining a copy of this software,
 * to deal in the Software without restriction. The above copyright notice and this permission
 * notice shall be included in all copies or substantial portions of the Software.
 */
'''


def run(tmp_path, monkeypatch, files, *argv):
    monkeypatch.chdir(tmp_path)
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    return main(argv=list(argv))


def test_headers_of_known_licenses_pass(tmp_path, monkeypatch, capsys):
    files = {'node.py': APACHE_PY, 'src/main.cpp': SPDX_CPP, 'include/lib.hpp': MIT_BLOCK, 'empty.py': ''}
    assert run(tmp_path, monkeypatch, files) == 0
    assert capsys.readouterr().out == 'No problems found, checked 4 files\n'


@pytest.mark.parametrize(('header', 'spdx'), [
    (APACHE_PY, 'Apache-2.0'), (SPDX_CPP, 'BSD-3-Clause'), (MIT_BLOCK, 'MIT'),
    ('# Permission is hereby granted, free of charge, to any person\n', 'MIT-0'),
    ('# GNU Lesser General Public License as published by the Free Software Foundation, version 3\n',
     'LGPL-3.0-only'),
    ('# GNU General Public License as published by the Free Software Foundation, version 3\n',
     'GPL-3.0-only'),
    ('# Some words of our own\n', '<unknown>'),
])
def test_the_license_is_read_from_the_first_comment_block(header, spdx):
    assert license_of(header_text(header)) == spdx


def test_files_without_notice_or_known_license_fail_one_line_each(tmp_path, monkeypatch, capsys):
    files = {'a.py': 'print(1)\n', 'b.py': '# Copyright 2024 Ann\n# All rights reserved.\n',
             'c.py': APACHE_PY}
    assert run(tmp_path, monkeypatch, files, '.') == 1
    assert capsys.readouterr().err.splitlines() == [
        'a.py: could not find copyright notice',
        'b.py: copyright=Copyright 2024 Ann, license=<unknown>',
        '2 errors, checked 3 files']


def test_a_packages_setup_py_and_hidden_folders_are_left_out(tmp_path, monkeypatch, capsys):
    files = {'package.xml': '<package/>', 'setup.py': 'print(1)\n', '.git/hook.py': 'print(1)\n',
             'notes.txt': 'no header', 'node.py': APACHE_PY}
    assert run(tmp_path, monkeypatch, files, '.', '--verbose') == 0
    assert capsys.readouterr().out.splitlines() == [
        'node.py: copyright=Copyright 2024 Ann Example, license=Apache-2.0',
        'No problems found, checked 1 files']


def test_a_missing_path_is_one_clear_line(tmp_path, monkeypatch, capsys):
    assert run(tmp_path, monkeypatch, {}, 'missing') == 1
    assert capsys.readouterr().err == 'ament_copyright: missing: no such file or directory\n'
