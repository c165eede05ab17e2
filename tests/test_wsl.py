"""`owl network` on a WSL 2 machine as it meets one: WSL_DISTRO_NAME set, and Microsoft's wslinfo on the PATH.

The verdicts themselves, for every mode and /proc/version, are src/tools/owl_cli/test/test_wsl_check.py's.
"""

import os


def test_owl_network_names_wsl_and_says_what_to_change(ros, tmp_path):
    wslinfo = tmp_path / 'wslinfo'
    wslinfo.write_text('#!/bin/sh\n[ "$1" = --networking-mode ] && echo nat\n')
    wslinfo.chmod(0o755)
    check = ros.command(['owl', 'network', '--discovery-time', '0.5', '--timeout', '0.2'], env={
        'WSL_DISTRO_NAME': 'Ubuntu-24.04', 'ROS_AUTOMATIC_DISCOVERY_RANGE': 'SUBNET',
        'PATH': f"{tmp_path}:{os.environ['PATH']}"})
    assert check.wait(60) == 1
    lines = check.lines
    assert lines[1].startswith('owl network: problem: WSL 2 with nat networking (from wslinfo): the Olive '
                               "modules on the laptop's USB Ethernet"), lines
    assert lines[1].endswith('then run wsl --shutdown in PowerShell and open Ubuntu again '
                             '(Windows 11 22H2 or later)'), lines
    assert 'Traceback' not in check.output
