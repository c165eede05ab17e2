"""config/fastdds.xml reaches Fast DDS, and Fast DDS parses it without complaint.

env.sh names the file in a variable the installed Fast DDS reads. Both failures are otherwise silent:
the move to Jazzy kept Fast DDS 3's variable name, which Fast DDS 2.14 ignores, and everything ran on
its defaults unnoticed.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

from env_sh import after_env_sh
from owl_common.processes import RosSandbox

ROOT = Path(__file__).resolve().parents[1]
PROFILE = ROOT / 'config' / 'fastdds.xml'
# Fast DDS 2.x (Jazzy) reads the first, Fast DDS 3 (Kilted on) the second.
VARIABLES = ('FASTRTPS_DEFAULT_PROFILES_FILE', 'FASTDDS_DEFAULT_PROFILES_FILE')
PARTICIPANT = ('import rclpy; rclpy.init(); rclpy.create_node("profile_probe").destroy_node(); '
               'rclpy.shutdown()')
ANSI_COLOUR = re.compile(r'\x1b\[[0-9;]*m')
XML_ERROR = re.compile(r'\[XML\w* Error\].*')


def variables_env_sh_sets() -> list[str]:
    """The profile variables that a fresh `source env.sh` points at config/fastdds.xml."""
    return [name for name, value in after_env_sh(VARIABLES, unset=VARIABLES).items() if value == str(PROFILE)]


def xml_errors(variables: list[str], profile: Path) -> list[str]:
    """The XML errors Fast DDS prints while a node starts with `variables` naming `profile`."""
    with RosSandbox() as sandbox:
        env = {name: value for name, value in sandbox.env.items() if name not in VARIABLES}
        env.update(dict.fromkeys(variables, str(profile)))
        done = subprocess.run([sys.executable, '-c', PARTICIPANT], env=env, capture_output=True,
                              text=True, timeout=60, check=False)
    output = ANSI_COLOUR.sub('', done.stdout + done.stderr)
    assert done.returncode == 0, output
    return XML_ERROR.findall(output)


def test_fast_dds_reads_and_parses_our_profile(tmp_path):
    variables = variables_env_sh_sets()
    assert variables, f'env.sh points none of {VARIABLES} at {PROFILE}'
    # Fast DDS says nothing about a file it never opens; a broken copy shows that it opens ours.
    text = PROFILE.read_text()
    assert '<rtps>' in text
    broken = tmp_path / 'broken.xml'
    broken.write_text(text.replace('<rtps>', '<rtps><no_such_setting/>', 1))
    assert xml_errors(variables, broken), f'Fast DDS ignores {variables}'
    assert xml_errors(variables, PROFILE) == []
