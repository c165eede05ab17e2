"""What a class server costs per student, and how many students a machine holds (run as root).

`owl class serve` for --students new accounts; then, one student at a time, as a student does it:
log in, wait for JupyterLab, open a terminal and run a command (the login time), start the kit and
the robot view there (`ros2 launch robot_view robot_view.launch.py`, no browser watching), and
measure over --seconds, for every student running so far: the camera's frame rate and the IMU's
rate as a subscriber in each student's own terminal receives them (the probe's CPU is theirs then),
and then each student's CPU (% of one core, every process of their account) and memory (resident,
summed). It stops adding students when any student's camera falls below 90 % of 30 fps or IMU
below 90 % of 100 Hz, or when one more student's server does not start in 90 s: the students
before that one are what this machine holds. From the CPU and memory per student it estimates a
16-core, 64 GB server (the figure a teacher plans with).

Baseline, in the same run: the same launch as root outside the hub (its CPU and memory), so the
ratio says what the class server adds to a student's kit.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from measure import cpu_seconds
from olive_kit.description import CAMERA_TOPIC, IMU_TOPIC
from owl_common.processes import RosSandbox

TESTS = Path(__file__).resolve().parents[1] / 'tests'
sys.path.insert(0, str(TESTS))  # the class server's test harness: one piece of code for it
from class_harness import Hub, Terminal, Visitor, in_a_thread, logged_in  # noqa: E402

CAMERA_FPS, IMU_HZ, ENOUGH = 30.0, 100.0, 0.9
SERVER_CORES, SERVER_GB = 16, 64
LAUNCH = 'ros2 launch robot_view robot_view.launch.py'
LOGIN_TIMEOUT = 90.0  # s: a student whose server does not answer by then is one too many


# Counts the camera's frames and the IMU's messages over N seconds, run in a student's own terminal:
# a node of another account (the bench runs as root) hears nothing of theirs, because Fast DDS's
# shared-memory transport, which it prefers on one machine, does not cross accounts.
PROBE = f"""
import sys, time
import rclpy
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import CompressedImage, Imu
rclpy.init()
node = rclpy.create_node('class_bench_probe')
counts = {{'camera': 0, 'imu': 0}}
def count(key):
    def heard(_):
        counts[key] += 1
    return heard
node.create_subscription(CompressedImage, '{CAMERA_TOPIC}', count('camera'), qos_profile_sensor_data)
node.create_subscription(Imu, '{IMU_TOPIC}', count('imu'), qos_profile_sensor_data)
deadline = time.monotonic() + 30
while counts['camera'] == 0 or counts['imu'] == 0:
    rclpy.spin_once(node, timeout_sec=0.1)
    if time.monotonic() > deadline:
        break
seconds = float(sys.argv[1])
counts = {{'camera': 0, 'imu': 0}}
end = time.monotonic() + seconds
while time.monotonic() < end:
    rclpy.spin_once(node, timeout_sec=0.05)
print('RATES camera %.1f imu %.1f' % (counts['camera'] / seconds, counts['imu'] / seconds))
"""
RATES = re.compile(r'RATES camera ([0-9.]+) imu ([0-9.]+)')


async def rates_of(students: dict[str, Visitor], probe: Path,
                   seconds: float) -> dict[str, tuple[float, float]]:
    """Each student's (camera fps, IMU Hz), counted at once in a terminal of each."""
    async def one(name: str) -> tuple[float, float]:
        async with Terminal(students[name], name) as terminal:
            found = RATES.search(await terminal.run(f'python {probe} {seconds}', timeout=seconds + 60))
        return (float(found.group(1)), float(found.group(2))) if found else (0.0, 0.0)

    measured = await asyncio.gather(*(one(name) for name in students))
    return dict(zip(students, measured, strict=True))


def account_usage(name: str) -> tuple[float, float]:
    """(CPU seconds so far, resident MB) summed over every process of the account."""
    listing = subprocess.run(['ps', '-o', 'pid=,rss=', '-u', name], capture_output=True, text=True,
                             check=False)
    cpu = memory = 0.0
    for line in listing.stdout.split('\n'):
        if line.strip():
            pid, rss = line.split()
            try:
                cpu += cpu_seconds(int(pid))
            except OSError:
                continue  # ended meanwhile
            memory += int(rss) / 1024
    return cpu, memory


def usage(names: list[str], seconds: float) -> dict[str, tuple[float, float]]:
    """Each account's (CPU % of one core over seconds, resident MB at the end)."""
    before = {name: account_usage(name)[0] for name in names}
    time.sleep(seconds)  # the window the CPU is counted over
    found = {}
    for name in names:
        cpu, memory = account_usage(name)
        found[name] = (100 * (cpu - before[name]) / seconds, memory)
    return found


def baseline(seconds: float) -> tuple[float, float]:
    """(CPU % of a core, resident MB) of the same launch as root, outside the hub."""
    sandbox = RosSandbox()
    try:
        launch = sandbox.command([*LAUNCH.split(), 'port:=0', 'web_port:=0'], label='robot_view.launch')
        launch.wait_for(r'robot_view: open ', 60)
        time.sleep(3)  # past the start-up's own CPU
        pids = [int(pid) for pid in subprocess.run(['pgrep', '-g', str(os.getpgid(launch.popen.pid))],
                                                   capture_output=True, text=True).stdout.split()]
        start = sum(cpu_seconds(pid) for pid in pids)
        time.sleep(seconds)
        cpu = sum(cpu_seconds(pid) for pid in pids) - start
        memory = sum(int(Path(f'/proc/{pid}/statm').read_text().split()[1]) * os.sysconf('SC_PAGE_SIZE')
                     for pid in pids) / 2**20
        return 100 * cpu / seconds, memory
    finally:
        sandbox.close()


def main() -> int:
    """Measure; exit code 0, or 2 with one line when it cannot run."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--students', type=int, default=6, choices=range(1, 101), metavar='1..100',
                        help='the most students to add (default 6)')
    parser.add_argument('--seconds', type=float, default=10.0, help='each measuring window (default 10)')
    args = parser.parse_args()
    if os.geteuid() != 0:
        print('class_server.py: run it as root (it makes Unix accounts)', file=sys.stderr)
        return 2
    base_cpu, base_memory = baseline(args.seconds)
    print(f'baseline: the kit and robot view as root, no hub: {base_cpu:.0f} % of a core, '
          f'{base_memory:.0f} MB')
    started = time.monotonic()
    hub = Hub.open(students=args.students)
    print(f'hub: started in {time.monotonic() - started:.1f} s (with the lab built if the checkout changed)')
    running: dict[str, Visitor] = {}
    holds = 0
    folder = Path(tempfile.mkdtemp(prefix='owl-class-bench-'))
    folder.chmod(0o755)
    probe = folder / 'probe.py'
    probe.write_text(PROBE)
    probe.chmod(0o644)
    try:
        for name in hub.students:
            began = time.monotonic()
            try:
                student = logged_in(hub, [name], timeout=LOGIN_TIMEOUT)[name]
            except AssertionError as error:  # the machine is too busy to start one more JupyterLab
                print(f'student {len(running) + 1}: cannot log in ({error})')
                break

            async def start(name: str = name, student: Visitor = student, began: float = began) -> float:
                async with Terminal(student, name) as terminal:
                    await terminal.run('true')
                    ready = time.monotonic() - began
                    await terminal.run(f'{LAUNCH} > robot_view.log 2>&1 &')
                return ready

            login = in_a_thread(start())
            running[name] = student
            rates = in_a_thread(rates_of(running, probe, args.seconds))  # also past the kit's start-up
            accounts = usage(list(running), args.seconds)
            fps, hz = rates[name]
            cpu, memory = accounts[name]
            print(f'student {len(running)}: login to a working terminal {login:.1f} s; their account: '
                  f'{cpu:.0f} % of a core, {memory:.0f} MB; camera {fps:.1f} fps, IMU {hz:.0f} Hz')
            worst_fps = min(f for f, _ in rates.values())
            worst_hz = min(h for _, h in rates.values())
            per_cpu = sum(c for c, _ in accounts.values()) / len(accounts)
            per_memory = sum(m for _, m in accounts.values()) / len(accounts)
            print(f'  with {len(running)} students: lowest camera {worst_fps:.1f} fps, lowest IMU '
                  f'{worst_hz:.0f} Hz, per student {per_cpu:.0f} % of a core and {per_memory:.0f} MB')
            if worst_fps < ENOUGH * CAMERA_FPS or worst_hz < ENOUGH * IMU_HZ:
                break
            holds = len(running)
    finally:
        hub.close()
        shutil.rmtree(folder, ignore_errors=True)
    cores = os.cpu_count() or 1
    at_capacity = 'or more' if holds == len(hub.students) else ''
    print(f'this machine ({cores} cores) holds {holds} {at_capacity} students with the kit running '
          f'(camera >= {ENOUGH * CAMERA_FPS:.0f} fps, IMU >= {ENOUGH * IMU_HZ:.0f} Hz)')
    by_cpu = int(SERVER_CORES * 100 * ENOUGH / per_cpu) if per_cpu else 0
    by_memory = int(SERVER_GB * 1024 * ENOUGH / per_memory) if per_memory else 0
    print(f'a {SERVER_CORES}-core, {SERVER_GB} GB server: about {min(by_cpu, by_memory)} students '
          f'({by_cpu} by CPU at {per_cpu:.0f} % each, {by_memory} by memory at {per_memory:.0f} MB each)')
    print(f"ratio (a student's account on the class server / the same kit as root): CPU "
          f'{per_cpu / base_cpu:.2f}, memory {per_memory / base_memory:.2f}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
