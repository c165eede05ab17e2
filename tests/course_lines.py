"""The course's lines that the listings use, kept as digests so a clone without the course can check them.

tests/course_listings/course_lines.sha256 holds one SHA-256 per distinct line (stripped) of the
listings that is a line of the course (`../shared/course/*.txt`), not the course's text.
test_course_listings.py checks every listing line against it; where the course is beside the clone,
it also checks that the file is exactly what the course gives. `python tests/course_lines.py` writes
it again from the course.
"""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path

LISTINGS = Path(__file__).parent / 'course_listings'
DIGESTS = LISTINGS / 'course_lines.sha256'
COURSE = Path(__file__).resolve().parents[2] / 'shared' / 'course'


def digest(line: str) -> str:
    return hashlib.sha256(line.strip().encode()).hexdigest()


def listing_lines() -> dict[str, list[str]]:
    """Each listing's name and its lines."""
    return {path.name: path.read_text().splitlines() for path in sorted(LISTINGS.glob('s*.py'))}


def course_digests(course: Path) -> set[str]:
    return {digest(line) for path in course.glob('*.txt') for line in path.read_text().splitlines()}


def digests_from_course(course: Path) -> list[str]:
    """What DIGESTS must hold: the digests of the listings' lines that the course has, sorted."""
    in_course = course_digests(course)
    return sorted({digest(line) for lines in listing_lines().values() for line in lines} & in_course)


def stored_digests() -> set[str]:
    return set(DIGESTS.read_text().split())


def main() -> int:
    if not COURSE.is_dir():
        print(f'course_lines: no course at {COURSE}', file=sys.stderr)
        return 1
    DIGESTS.write_text(''.join(f'{line}\n' for line in digests_from_course(COURSE)))
    print(f'course_lines: wrote {DIGESTS}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
