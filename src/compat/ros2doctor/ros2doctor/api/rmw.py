"""The middleware (RMW) this ROS 2 uses."""

from __future__ import annotations

from ros2doctor.api import DoctorReport, Report


class RMWReport(DoctorReport):
    """RMW MIDDLEWARE: the rmw implementation's name."""

    def category(self) -> str:
        """'middleware'."""
        return 'middleware'

    def report(self) -> Report:
        """Middleware name, e.g. rmw_fastrtps_cpp."""
        from rclpy.utilities import get_rmw_implementation_identifier

        report = Report('RMW MIDDLEWARE')
        report.add_to_report('middleware name', get_rmw_implementation_identifier())
        return report
