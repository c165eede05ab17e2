"""Packages: the installed ROS 2 packages against the versions this project pins.

Upstream compares local versions with the newest release in the online rosdistro index. Here
ROS 2 comes from PyPI wheels pinned in $OWL_ROOT/requirements.txt, so what matters is whether
the venv still holds those pins.
"""

from __future__ import annotations

import os
import re
import xml.etree.ElementTree as ET
from importlib import metadata
from pathlib import Path

from ros2doctor.api import DoctorCheck, DoctorReport, Report, Result
from ros2doctor.api.format import doctor_warn
from ros2doctor.api.platform import SUPPORT_ENDS

PIN = re.compile(r'^(ros-[a-z0-9-]+)==([^\s;#]+)', re.M)


def ros_pins() -> dict[str, str]:
    """Wheel name -> pinned version, from $OWL_ROOT/requirements.txt (empty without one)."""
    root = os.environ.get('OWL_ROOT')
    path = Path(root) / 'requirements.txt' if root else None
    if path is None or not path.is_file():
        return {}
    return dict(PIN.findall(path.read_text()))


def package_of_wheel(wheel: str) -> str:
    """'ros-jazzy-std-msgs' -> 'std_msgs'; distro-less 'ros-ament-index-python' -> 'ament_index_python'."""
    name = wheel.removeprefix('ros-')
    distro, _, rest = name.partition('-')
    if distro in (*SUPPORT_ENDS, 'rolling') and rest:
        name = rest
    return name.replace('-', '_')


def local_versions() -> dict[str, str]:
    """ROS package -> the version its installed package.xml declares."""
    from ament_index_python.packages import get_packages_with_prefixes

    versions = {}
    for name, prefix in get_packages_with_prefixes().items():
        manifest = Path(prefix) / 'share' / name / 'package.xml'
        try:
            versions[name] = ET.parse(manifest).getroot().findtext('version') or 'unknown'
        except (OSError, ET.ParseError):
            continue
    return dict(sorted(versions.items()))


class PackageCheck(DoctorCheck):
    """Every pinned ROS 2 wheel is installed at its pin."""

    def category(self) -> str:
        """'package'."""
        return 'package'

    def check(self) -> Result:
        """A warning per wheel missing or at another version than its pin."""
        result = Result()
        for wheel, pinned in ros_pins().items():
            try:
                local = metadata.version(wheel)
            except metadata.PackageNotFoundError:
                doctor_warn(f'{package_of_wheel(wheel)} is not installed (pinned: {pinned}). '
                            "Run 'make setup'.")
                result.add_warning()
                continue
            if local != pinned:
                doctor_warn(f"{package_of_wheel(wheel)} is not at its pinned version. local: {local} != "
                            f"pinned: {pinned}. Run 'make setup'.")
                result.add_warning()
        return result


class PackageReport(DoctorReport):
    """PACKAGE VERSIONS: each installed ROS package, with its pin where the project pins it."""

    def category(self) -> str:
        """'package'."""
        return 'package'

    def report(self) -> Report:
        """`<package>: pinned=<version or N/A>, local=<version>`.

        A pinned package's local version is its installed wheel's (a wheel's version can differ from
        its package.xml's), any other package's the one its package.xml declares.
        """
        wheels = {package_of_wheel(wheel): (wheel, version) for wheel, version in ros_pins().items()}
        report = Report('PACKAGE VERSIONS')
        for name, local in local_versions().items():
            pinned = 'N/A'
            if name in wheels:
                wheel, pinned = wheels[name]
                try:
                    local = metadata.version(wheel)
                except metadata.PackageNotFoundError:
                    local = f'{local} (not the pinned wheel)'
            report.add_to_report(name, f'pinned={pinned}, local={local}')
        return report
