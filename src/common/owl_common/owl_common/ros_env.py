"""ROS_DOMAIN_ID, read one way by every tool of ours (the ros2 command, its daemon, ros2 doctor, owl).

rcl takes an unset or empty ROS_DOMAIN_ID as domain 0. Fast DDS ends the process for a domain
whose ports do not fit under its default port base, so anything but a whole number from 0 to
MAX_DOMAIN_ID is refused here, with one sentence saying what is wrong, before a participant is made.
"""

from __future__ import annotations

import os
from collections.abc import Mapping

VARIABLE = 'ROS_DOMAIN_ID'
MAX_DOMAIN_ID = 232  # the highest whose discovery and user ports fit (Fast DDS's default port base)


class DomainIdError(ValueError):
    """ROS_DOMAIN_ID holds something no node can use; its text says what and which values are."""


def domain_id(environ: Mapping[str, str] | None = None) -> int:
    """The ROS domain of environ (default: this process's environment); DomainIdError for a bad one."""
    text = (os.environ if environ is None else environ).get(VARIABLE, '')
    if not text:
        return 0
    if not (text.isascii() and text.isdigit()) or int(text) > MAX_DOMAIN_ID:
        raise DomainIdError(f"{VARIABLE} is '{text}'; it must be a number from 0 to {MAX_DOMAIN_ID}")
    return int(text)
