"""The venv's repair of Fast DDS's enable order: a new participant hears every running one at once.

Fast DDS 2.14.5 announces a new participant before it listens, and dropped about 4 in 10 of the
running participants' answers; the newcomer then learnt of each from its next periodic
announcement. src/tools/owl_venv_hooks/owl_fastdds_enable_order.c swaps the order for the pinned
build and steps aside for any other.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from owl_common.processes import RosSandbox

ROOT = Path(__file__).resolve().parents[1]
PROFILE = ROOT / 'config' / 'fastdds.xml'
LIBRARY = Path(sys.prefix) / 'lib' / 'libowl_fastdds_enable_order.so'
NOT_CALLED, RECEIVERS_FIRST, UPSTREAM_ORDER = 0, 1, 2
ANNOUNCEMENT_PERIOD = 15  # s: running participants re-announce themselves this rarely here
HEARD_WITHIN = 5.0  # s: a newcomer that missed an answer would mostly wait longer
RUNNING = 4
NEWCOMERS = 6

ORDER_PROBE = f'''
import ctypes, rclpy
order = ctypes.CDLL({str(LIBRARY)!r}).owl_fastdds_enable_order
print('before', order())
rclpy.init()
node = rclpy.create_node('enable_order_probe')
print('after', order())
'''

RUNNING_NODE = '''
import sys, rclpy
rclpy.init()
node = rclpy.create_node(sys.argv[1])
print('up', flush=True)
rclpy.spin(node)
'''

NEWCOMER = '''
import sys, time, rclpy
expected = set(sys.argv[1:])
rclpy.init()
node = rclpy.create_node('newcomer')
start = time.monotonic()
while time.monotonic() - start < LIMIT:
    rclpy.spin_once(node, timeout_sec=0.01)
    if expected <= set(node.get_node_names()):
        print(f'heard all after {time.monotonic() - start:.3f} s')
        break
else:
    print('missing', sorted(expected - set(node.get_node_names())))
'''


def test_a_participant_starts_receiving_before_it_announces_itself():
    with RosSandbox() as sandbox:
        done = subprocess.run([sys.executable, '-c', ORDER_PROBE], env=sandbox.env, capture_output=True,
                              text=True, timeout=60, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ['before', str(NOT_CALLED), 'after', str(RECEIVERS_FIRST)], (
        f'{done.stdout}: the pinned Fast DDS is not the build owl_fastdds_enable_order.c was written for')


def slow_announcements(tmp_path: Path) -> Path:
    """config/fastdds.xml with participants that re-announce themselves every ANNOUNCEMENT_PERIOD s."""
    text = PROFILE.read_text()
    period = '<leaseAnnouncement><sec>0</sec><nanosec>500000000</nanosec></leaseAnnouncement>'
    assert period in text
    text = text.replace(period, f'<leaseAnnouncement><sec>{ANNOUNCEMENT_PERIOD}</sec></leaseAnnouncement>')
    text = text.replace('<leaseDuration><sec>10</sec></leaseDuration>',
                        f'<leaseDuration><sec>{3 * ANNOUNCEMENT_PERIOD}</sec></leaseDuration>')
    profile = tmp_path / 'slow_announcements.xml'
    profile.write_text(text)
    return profile


def test_each_newcomer_hears_every_running_participant_without_waiting_for_its_announcement(tmp_path):
    # A lost answer costs a newcomer up to ANNOUNCEMENT_PERIOD s; with every answer heard, the
    # graph is complete well within HEARD_WITHIN s (endpoints and node names follow the answers).
    slow = {'FASTRTPS_DEFAULT_PROFILES_FILE': str(slow_announcements(tmp_path))}
    names = [f'running_{i}' for i in range(RUNNING)]
    newcomer = NEWCOMER.replace('LIMIT', str(HEARD_WITHIN))
    with RosSandbox() as sandbox:
        for name in names:
            running = sandbox.command([sys.executable, '-c', RUNNING_NODE, name], label=name, env={**slow})
            running.wait_for('up')
        verdicts = []
        for _ in range(NEWCOMERS):
            done = subprocess.run([sys.executable, '-c', newcomer, *names], env={**sandbox.env, **slow},
                                  capture_output=True, text=True, timeout=60, check=False)
            assert done.returncode == 0, done.stderr
            verdicts.append(done.stdout.strip())
    assert all(verdict.startswith('heard all') for verdict in verdicts), verdicts


FAKE_FAST_DDS = r'''
#include <stdio.h>
void participant_enable(void *self) __asm__("_ZN8eprosima8fastrtps4rtps19RTPSParticipantImpl6enableEv");
void participant_enable(void *self) { printf("its own enable(%p)\n", self); fflush(stdout); }
void make_participant(void) { participant_enable((void *)0x1234); }
'''

STEP_ASIDE_PROBE = '''
import ctypes, os, sys
repair = ctypes.CDLL(sys.argv[1], mode=os.RTLD_GLOBAL)
ctypes.CDLL(sys.argv[2]).make_participant()
print('order', repair.owl_fastdds_enable_order())
'''


def test_another_fast_dds_build_keeps_its_own_enable(tmp_path):
    compiler = shutil.which('cc') or shutil.which('gcc')
    if compiler is None:
        pytest.fail('no C compiler: make setup needs one too')
    fake = tmp_path / 'libfake_fastrtps.so'
    source = tmp_path / 'fake_fastrtps.c'
    source.write_text(FAKE_FAST_DDS)
    subprocess.run([compiler, '-shared', '-fPIC', '-o', str(fake), str(source)], check=True, timeout=60)
    done = subprocess.run([sys.executable, '-c', STEP_ASIDE_PROBE, str(LIBRARY), str(fake)],
                          capture_output=True, text=True, timeout=60, check=False,
                          env={k: v for k, v in os.environ.items() if k != 'LD_PRELOAD'})
    assert done.returncode == 0, done.stderr
    # The call reached the repair (it is loaded first) and was passed on unchanged.
    assert re.fullmatch(r'its own enable\(0x1234\)\norder \d\n', done.stdout), done.stdout
    assert int(done.stdout.split()[-1]) == UPSTREAM_ORDER


BROKEN_LIBRARY_PROBE = '''
import sys
import owl_rclpy_repair
sys.prefix = sys.argv[1]
owl_rclpy_repair.load_fastdds_enable_order()
print('went on')
'''


def test_a_library_that_cannot_load_is_one_line_and_rclpy_goes_on(tmp_path):
    (tmp_path / 'lib').mkdir()
    (tmp_path / 'lib' / LIBRARY.name).write_text('not a shared library\n')
    done = subprocess.run([sys.executable, '-c', BROKEN_LIBRARY_PROBE, str(tmp_path)], capture_output=True,
                          text=True, timeout=60, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout == 'went on\n'
    [line] = done.stderr.splitlines()
    assert line.startswith('owl: Fast DDS enable-order repair not loaded ('), line
    assert line.endswith('run make setup'), line
