"""The ROS environment, read one way by every tool of ours: the domain, the discovery range, the peers.

rcl takes an unset or empty ROS_DOMAIN_ID as domain 0. Fast DDS ends the process for a domain
whose ports do not fit under its default port base, so anything but a whole number from 0 to
MAX_DOMAIN_ID is refused here, with one sentence saying what is wrong, before a participant is made.
"""

from __future__ import annotations

import os
from collections.abc import Mapping

MAX_DOMAIN_ID = 232  # the highest whose discovery and user ports fit (Fast DDS's default port base)


class DomainIdError(ValueError):
    """ROS_DOMAIN_ID holds something no node can use; its text says what and which values are."""


def _environment(environ: Mapping[str, str] | None) -> Mapping[str, str]:
    return os.environ if environ is None else environ


def domain_id(environ: Mapping[str, str] | None = None) -> int:
    """The ROS domain of environ (default: this process's environment); DomainIdError for a bad one."""
    text = _environment(environ).get('ROS_DOMAIN_ID', '')
    if not text:
        return 0
    if not (text.isascii() and text.isdigit()) or int(text) > MAX_DOMAIN_ID:
        raise DomainIdError(f"ROS_DOMAIN_ID is '{text}'; it must be a number from 0 to {MAX_DOMAIN_ID}")
    return int(text)


def discovery_range(environ: Mapping[str, str] | None = None) -> str:
    """ROS_AUTOMATIC_DISCOVERY_RANGE in capitals; SUBNET when it is unset, empty or SYSTEM_DEFAULT."""
    value = (_environment(environ).get('ROS_AUTOMATIC_DISCOVERY_RANGE') or 'SUBNET').upper()
    return 'SUBNET' if value == 'SYSTEM_DEFAULT' else value


def static_peers(environ: Mapping[str, str] | None = None) -> list[str]:
    """The addresses in ROS_STATIC_PEERS (separated by ';', blanks around them ignored)."""
    text = _environment(environ).get('ROS_STATIC_PEERS') or ''
    return [peer.strip() for peer in text.split(';') if peer.strip()]
