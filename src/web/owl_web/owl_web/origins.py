"""Who may use our pages: loopback Host and Origin, and the proxies the user trusts; page ports.

Plain functions without aiohttp, so a command that only checks its arguments (`owl`, a page's
--port) starts without loading the web server (0.2 s of CPU).
"""

from __future__ import annotations

import argparse
import ipaddress
import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any
from urllib.parse import urlsplit

from owl_web.owner_only import OwnerOnly


def is_loopback_name(hostname: str) -> bool:
    """Whether a URL's host name is this machine: 'localhost' or a loopback IP address."""
    if hostname == 'localhost':
        return True
    try:
        return ipaddress.ip_address(hostname).is_loopback
    except ValueError:
        return False


DEFAULT_PORTS = {'http': 80, 'https': 443}


@dataclass(frozen=True)
class TrustedOrigins:
    """The public origins of a proxy in front of our pages, whose Host and Origin they accept too.

    A class server's proxy (JupyterHub with jupyter-server-proxy) passes the browser's Host and Origin
    on unchanged: https://hub.example.edu is not a loopback address, so without this our pages would
    refuse their own students. Only what the user configures is trusted, in OWL_TRUSTED_ORIGINS
    (origins such as https://hub.example.edu, separated by spaces or commas); headers that a client
    writes itself (X-Forwarded-Host, Forwarded, ...) are never read.
    """

    origins: frozenset[str] = frozenset()  # scheme://host[:port], the port only when not the default
    hosts: frozenset[str] = frozenset()    # what a browser sends as Host for them

    @classmethod
    def parse(cls, text: str) -> TrustedOrigins:
        """The origins in text; ValueError naming the first that is not an origin."""
        origins, hosts = set(), set()
        for item in text.replace(',', ' ').split():
            parts = urlsplit(item.lower())
            try:
                port = parts.port
            except ValueError:
                port = -1
            if parts.scheme not in DEFAULT_PORTS or not parts.hostname or parts.path not in ('', '/') \
                    or parts.query or parts.fragment or parts.username or port == -1:
                raise ValueError(f"OWL_TRUSTED_ORIGINS: '{item}' is not an origin such as "
                                 'https://hub.example.edu or http://lab.local:8000')
            default = port in (None, DEFAULT_PORTS[parts.scheme])
            netloc = parts.hostname if default else f'{parts.hostname}:{port}'
            origins.add(f'{parts.scheme}://{netloc}')
            hosts.add(netloc)
        return cls(frozenset(origins), frozenset(hosts))

    @classmethod
    def from_environment(cls, environ: Mapping[str, str] | None = None) -> TrustedOrigins:
        """OWL_TRUSTED_ORIGINS of the environment (none when unset); ValueError when it is malformed."""
        return cls.parse((os.environ if environ is None else environ).get('OWL_TRUSTED_ORIGINS', ''))


def foreign_request(host: str, origin: str | None, trusted: TrustedOrigins = TrustedOrigins()) -> str | None:
    """Why a request does not come from this machine's own pages (or a trusted proxy's), or None.

    Listening on 127.0.0.1 keeps other machines out, not other web sites open in the student's
    browser: the Host check stops DNS rebinding (a site's name re-pointed at 127.0.0.1), the Origin
    check another site's page sending requests or opening the WebSocket (which could drive the robot).
    Clients that are not browsers send no Origin.
    """
    hostname = urlsplit(f'//{host}').hostname or ''
    if not is_loopback_name(hostname) and host.lower() not in trusted.hosts:
        return f"refused: Host '{host}' is not a loopback address or a trusted origin's"
    if origin is not None and not is_loopback_name(urlsplit(origin).hostname or '') \
            and origin.lower() not in trusted.origins:
        return f'refused: a page of {origin} may not use this server'
    return None


def request_refusal(headers: Mapping[str, str], transport: Any, trusted: TrustedOrigins,
                    owner_only: OwnerOnly) -> str | None:
    """Why a request may not reach a page or the front door (foreign_request, owner_only), or None."""
    return (owner_only.refusal(transport)
            or foreign_request(headers.get('Host', ''), headers.get('Origin'), trusted))


def port_number(text: str) -> int:
    """Argparse's type for a page's --port: 0..65535 (0 picks a free one)."""
    if not text.isdigit() or int(text) > 65535:
        raise argparse.ArgumentTypeError(f"'{text}' is not a port number (0..65535)")
    return int(text)
