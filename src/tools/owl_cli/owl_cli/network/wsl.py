r"""`owl network` on Windows' WSL: which WSL, which networking mode, and what to change for the kit.

Facts from Microsoft's WSL documentation (learn.microsoft.com/windows/wsl: networking, wsl-config):
- WSL 2 runs a real Linux kernel whose release names "microsoft" (lower case, e.g.
  5.15.167.4-microsoft-standard-WSL2); WSL 1's says "Microsoft". WSL sets WSL_DISTRO_NAME.
- `wslinfo --networking-mode` (WSL 2.0 and later) prints the mode in effect: nat, mirrored, bridged,
  none, virtioproxy (consomme from 2.9). NAT is the default.
- In NAT mode WSL has a virtual network of its own: the laptop's USB Ethernet, where the Olive
  modules are (10.42.0.x), is not WSL's, and DDS discovery's multicast does not cross the NAT. Only
  TCP ports that WSL binds on 127.0.0.1 (or all addresses) are forwarded to Windows' localhost, which
  is why our pages have one front door on 127.0.0.1.
- Mirrored mode (Windows 11 22H2 or later: `networkingMode=mirrored` under [wsl2] in
  %UserProfile%\.wslconfig, then `wsl --shutdown`) gives WSL the laptop's own interfaces, with
  multicast. Inbound traffic then passes the Hyper-V firewall (on by default since WSL 2.0.9): where
  modules answer but ROS 2 finds none of their nodes, allowing inbound traffic there is the fix
  Microsoft documents (HYPER_V_ALLOW).
"""

from __future__ import annotations

import ipaddress
import shutil
import subprocess
from collections.abc import Mapping
from dataclasses import dataclass

# PowerShell, as administrator: the Hyper-V firewall lets inbound traffic reach WSL (the id is WSL's).
HYPER_V_ALLOW = ("Set-NetFirewallHyperVVMSetting -Name '{40E0AC32-46A5-438A-A0B2-2B479E8F2E90}' "
                 '-DefaultInboundAction Allow')
MIRRORED_FIX = (r'put networkingMode=mirrored under [wsl2] in %UserProfile%\.wslconfig on Windows, then '
                'run wsl --shutdown in PowerShell and open Ubuntu again (Windows 11 22H2 or later)')
NAT_LIKE = ('nat', 'virtioproxy', 'consomme')


@dataclass(frozen=True)
class WslFacts:
    """What this machine is, as far as WSL goes: version 0 when it is not WSL at all."""

    version: int              # 0: not WSL; 1 or 2
    distribution: str = ''    # WSL_DISTRO_NAME, e.g. Ubuntu-24.04
    networking: str = ''      # nat, mirrored, ...; '' when unknown
    networking_source: str = ''  # where networking came from: 'wslinfo' or 'the interfaces'


def wsl_version(kernel: str, environ: Mapping[str, str]) -> int:
    """2 for WSL 2, 1 for WSL 1, 0 for not WSL, from /proc/version's text and the environment."""
    if 'microsoft' in kernel or 'WSL2' in kernel:
        return 2
    if 'Microsoft' in kernel:
        return 1
    return 2 if environ.get('WSL_DISTRO_NAME') else 0


def networking_from_interfaces(names_and_addresses: list[tuple[str, str]]) -> str:
    """A guess at the networking mode without wslinfo: mirrored WSL has loopback0; NAT one 172.16/12 eth0."""
    names = {name for name, _ in names_and_addresses}
    if 'loopback0' in names:
        return 'mirrored'
    private = ipaddress.IPv4Network('172.16.0.0/12')
    if any(name == 'eth0' and ipaddress.IPv4Address(address) in private
           for name, address in names_and_addresses):
        return 'nat'
    return ''


def wsl_facts(kernel: str, environ: Mapping[str, str], wslinfo_mode: str,
              names_and_addresses: list[tuple[str, str]]) -> WslFacts:
    """The WSL facts from /proc/version's text, the environment, wslinfo's answer and the interfaces."""
    version = wsl_version(kernel, environ)
    if version == 0:
        return WslFacts(0)
    mode, source = wslinfo_mode.strip().lower(), 'wslinfo'
    if not mode:
        mode, source = networking_from_interfaces(names_and_addresses), 'the interfaces'
    return WslFacts(version, environ.get('WSL_DISTRO_NAME', ''), mode, source if mode else '')


def wsl_verdicts(facts: WslFacts) -> list[tuple[bool, str]]:
    """(ok, text) lines about WSL for `owl network`, each problem with what to change; [] when not WSL."""
    if facts.version == 0:
        return []
    distribution = facts.distribution or 'Ubuntu-24.04'
    if facts.version == 1:
        return [(False, 'this is WSL 1, which has no Linux network of its own for ROS 2; fix: in PowerShell '
                        f'run wsl --set-version {distribution} 2')]
    seen = f' (from {facts.networking_source})' if facts.networking_source else ''
    if facts.networking in NAT_LIKE:
        return [(False, f'WSL 2 with {facts.networking} networking{seen}: the Olive modules on the laptop\'s '
                        "USB Ethernet and DDS discovery's multicast do not reach it; fix: "
                        + MIRRORED_FIX)]
    if facts.networking == 'mirrored':
        return [(True, f'WSL 2 with mirrored networking{seen}: the laptop\'s interfaces are this machine\'s; '
                       'pages open in the Windows browser at the front door (owl pages)')]
    mode = facts.networking or 'an unknown'
    return [(False, f'WSL 2 with {mode} networking{seen}: the kit needs mirrored networking; fix: '
                    + MIRRORED_FIX)]


def wslinfo_networking_mode() -> str:
    """What `wslinfo --networking-mode` prints ('' without wslinfo, as outside WSL or before WSL 2.0)."""
    program = shutil.which('wslinfo')
    if program is None:
        return ''
    try:
        result = subprocess.run([program, '--networking-mode'], capture_output=True, text=True, timeout=5,
                                check=False)
    except (OSError, subprocess.TimeoutExpired):
        return ''
    return result.stdout.strip() if result.returncode == 0 else ''
