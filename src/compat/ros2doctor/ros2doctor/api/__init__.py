"""What a check or report is, and running them (upstream's ros2doctor.api names).

Checks are the entry points of the group `ros2doctor.checks` (DoctorCheck subclasses), reports
those of `ros2doctor.report` (DoctorReport subclasses); a third party adds its own there.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from ros2doctor.api.format import doctor_warn

CHECK_GROUP = 'ros2doctor.checks'
REPORT_GROUP = 'ros2doctor.report'


class Result:
    """What one check found: its error and warning counts."""

    def __init__(self) -> None:
        self.error = 0
        self.warning = 0

    def add_error(self) -> None:
        """Count one error."""
        self.error += 1

    def add_warning(self) -> None:
        """Count one warning."""
        self.warning += 1


class Report:
    """A report: a name and (key, value) items, printed in order."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.items: list[tuple[str, Any]] = []

    def add_to_report(self, item_name: str, item_info: Any) -> None:
        """Add one item."""
        self.items.append((item_name, item_info))


class DoctorCheck:
    """A check: category() names what it is about, check() returns a Result."""

    def category(self) -> str:
        """The category, e.g. 'network'."""
        raise NotImplementedError

    def check(self) -> Result:
        """Run the check; warnings and errors are said with doctor_warn/doctor_error as found."""
        raise NotImplementedError


class DoctorReport:
    """A report: category() names what it is about, report() returns a Report."""

    def category(self) -> str:
        """The category, e.g. 'network'."""
        raise NotImplementedError

    def report(self) -> Report:
        """Gather the report's items."""
        raise NotImplementedError


def _entry_points(group: str) -> list[Any]:
    from importlib.metadata import entry_points
    return sorted(entry_points().select(group=group), key=lambda point: point.name)


def _instances(group: str, kind: str, exclude: Iterable[str]) -> list[tuple[str, Any]]:
    """(entry point name, instance) of each loadable entry point of the group, by name."""
    found = []
    for point in _entry_points(group):
        if point.name in exclude:
            continue
        try:
            cls = point.load()
        except Exception as error:  # a third party's broken extension costs one line
            doctor_warn(f'{kind} entry point {point.name} fails to load: {error}')
            continue
        try:
            found.append((point.name, cls()))
        except Exception:
            doctor_warn(f'Unable to instantiate {kind.lower()} object from {point.name}.')
    return found


def run_checks(*, include_warnings: bool = False,
               exclude_packages: bool = False) -> tuple[set[str], int, int]:
    """Run every check: (categories that failed, number failed, number run).

    A check fails with an error, or with a warning when include_warnings; one that raises is said
    and not counted.
    """
    failed: set[str] = set()
    fail = total = 0
    exclude = {'PackageCheck'} if exclude_packages else set()
    for name, check in _instances(CHECK_GROUP, 'Check', exclude):
        try:
            category = check.category()
            result = check.check()
        except Exception as error:
            doctor_warn(f'Fail to call {name} class functions: {error}')
            continue
        total += 1
        if result.error > 0 or (include_warnings and result.warning > 0):
            fail += 1
            failed.add(category)
    return failed, fail, total


def generate_reports(*, categories: Iterable[str] | None = None,
                     exclude_packages: bool = False) -> list[Report]:
    """Every report (or those of the given categories), in entry point order."""
    wanted = None if categories is None else set(categories)
    exclude = {'PackageReport'} if exclude_packages else set()
    reports = []
    for name, report in _instances(REPORT_GROUP, 'Report', exclude):
        try:
            if wanted is not None and report.category() not in wanted:
                continue
            reports.append(report.report())
        except Exception as error:
            doctor_warn(f'Fail to call {name} class functions: {error}')
    return reports
