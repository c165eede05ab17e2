"""Platform: this machine, and the ROS 2 distribution it runs."""

from __future__ import annotations

import datetime
import os
import platform

from ros2doctor.api import DoctorCheck, DoctorReport, Report, Result
from ros2doctor.api.format import doctor_error, doctor_warn

# The distributions' support ends (REP 2000). Upstream looks them up online in the rosdistro
# index; this machine may have no internet, so the dates are kept here.
SUPPORT_ENDS = {
    'foxy': datetime.date(2023, 6, 20),
    'galactic': datetime.date(2022, 12, 9),
    'humble': datetime.date(2027, 5, 31),
    'iron': datetime.date(2024, 12, 4),
    'jazzy': datetime.date(2029, 5, 31),
    'kilted': datetime.date(2026, 12, 31),
    'lyrical': datetime.date(2031, 5, 31),
}
DOCS = 'https://docs.ros.org'


def distribution_status(distro: str, today: datetime.date | None = None) -> str | None:
    """'active', 'end-of-life', 'rolling' (the development distribution), or None when unknown."""
    if distro == 'rolling':
        return 'rolling'
    end = SUPPORT_ENDS.get(distro)
    if end is None:
        return None
    return 'active' if (today or datetime.date.today()) <= end else 'end-of-life'


class PlatformCheck(DoctorCheck):
    """ROS_DISTRO is set to a distribution that is still supported."""

    def category(self) -> str:
        """'platform'."""
        return 'platform'

    def check(self) -> Result:
        """An unset ROS_DISTRO is an error; an unknown, development or ended distribution a warning."""
        result = Result()
        distro = os.environ.get('ROS_DISTRO')
        if not distro:
            doctor_error('ROS_DISTRO is not set.')
            result.add_error()
            return result
        status = distribution_status(distro)
        if status is None:
            doctor_warn(f'Distribution name {distro} is not found')
            result.add_warning()
        elif status == 'rolling':
            doctor_warn(f'Distribution {distro} is not fully supported or tested. To get more consistent '
                        f'features, download a stable version at {DOCS}')
            result.add_warning()
        elif status == 'end-of-life':
            doctor_warn(f'Distribution {distro} is no longer supported or deprecated. To get the latest '
                        f'features, download the new versions at {DOCS}')
            result.add_warning()
        return result


class PlatformReport(DoctorReport):
    """PLATFORM INFORMATION: the operating system and machine."""

    def category(self) -> str:
        """'platform'."""
        return 'platform'

    def report(self) -> Report:
        """system, platform info, release, processor."""
        report = Report('PLATFORM INFORMATION')
        report.add_to_report('system', platform.system())
        report.add_to_report('platform info', platform.platform())
        report.add_to_report('release', platform.release())
        report.add_to_report('processor', platform.processor() or platform.machine())
        return report


class RosdistroReport(DoctorReport):
    """ROS 2 INFORMATION: the distribution and its support."""

    def category(self) -> str:
        """'platform'."""
        return 'platform'

    def report(self) -> Report:
        """Distribution name, type, status and support end (empty without ROS_DISTRO)."""
        report = Report('ROS 2 INFORMATION')
        distro = os.environ.get('ROS_DISTRO')
        if not distro:
            return report
        report.add_to_report('distribution name', distro)
        report.add_to_report('distribution type', 'ros2')
        report.add_to_report('distribution status', distribution_status(distro) or 'unknown')
        if distro in SUPPORT_ENDS:
            report.add_to_report('supported until', SUPPORT_ENDS[distro].isoformat())
        return report
