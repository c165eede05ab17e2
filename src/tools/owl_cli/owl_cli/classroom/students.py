"""The class list a teacher gives `owl class serve --students FILE`: one student per line, `name password`.

Names are Unix account names: a lowercase letter, then lowercase letters and digits, at most 32 in
all. Blank lines and lines starting with # are skipped. The first wrong line is reported in one
line that names it, before anything is created.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

NAME = re.compile(r'[a-z][a-z0-9]{0,31}')
NAME_RULE = 'a lowercase letter, then lowercase letters and digits, at most 32'


class StudentsError(ValueError):
    """A class list or a name that cannot be used, in one line."""


@dataclass(frozen=True)
class Student:
    """One line of the class list."""

    name: str
    password: str


def name_problem(name: str) -> str | None:
    """Why name cannot be an account name here, or None when it can."""
    if NAME.fullmatch(name):
        return None
    return f'{name!r} is not a name of {NAME_RULE}'


def parse_students(text: str, source: str) -> list[Student]:
    """The students of a class list in order; StudentsError for the first wrong line."""
    students: dict[str, Student] = {}
    for number, line in enumerate(text.splitlines(), start=1):
        fields = line.split()
        if not fields or fields[0].startswith('#'):
            continue
        where = f'{source}, line {number}'
        if len(fields) != 2:
            raise StudentsError(f'{where}: expected "name password", got {len(fields)} field(s)')
        name, password = fields
        problem = name_problem(name)
        if problem:
            raise StudentsError(f'{where}: {problem}')
        if name in students:
            raise StudentsError(f'{where}: {name!r} is listed twice')
        students[name] = Student(name, password)
    if not students:
        raise StudentsError(f'{source}: no student (one per line: name password)')
    return list(students.values())
