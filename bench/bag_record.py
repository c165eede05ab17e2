"""`ros2 bag record` under load: messages in vs messages written, against a bare rclpy subscriber.

A publisher process sends a 30 fps camera (640x480 rgb8 sensor_msgs/Image, 0.9 MB a frame of noise,
which compression cannot shrink) and a
1 kHz std_msgs/Int64 stream for --seconds, once the recorder and the baseline have both matched.
First the baseline, a bare rclpy node subscribing as the recorder does (raw, reliable, 1000 deep)
and only counting, then `ros2 bag record`, each alone with the publisher. Printed: per topic, sent
and received by each; the recorder's share written, and its ratio to the baseline's share (target
1.00: the recorder loses nothing a bare subscriber gets; a written share of 1.000 loses nothing).
"""

from __future__ import annotations

import argparse
import signal
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

import yaml
from owl_common.processes import RosSandbox

TOPICS = ('/camera', '/fast')

PUBLISHER = textwrap.dedent('''
    import os, sys, time
    import rclpy
    from rclpy.duration import Duration
    from rclpy.qos import HistoryPolicy, QoSProfile
    from sensor_msgs.msg import Image
    from std_msgs.msg import Int64

    seconds, subscribers = float(sys.argv[1]), int(sys.argv[2])
    rclpy.init()
    node = rclpy.create_node('bag_bench_publisher')
    # KEEP_ALL: a sample leaves the publisher's history only once every reader has it, so what is
    # lost is lost by a reader, not overwritten before a late acknowledgement.
    keep_all = QoSProfile(depth=1, history=HistoryPolicy.KEEP_ALL)
    camera = node.create_publisher(Image, '/camera', keep_all)
    fast = node.create_publisher(Int64, '/fast', keep_all)
    while min(camera.get_subscription_count(), fast.get_subscription_count()) < subscribers:
        rclpy.spin_once(node, timeout_sec=0.05)
    time.sleep(0.5)
    image = Image(height=480, width=640, encoding='rgb8', step=640 * 3, data=os.urandom(640 * 480 * 3))
    sent = {'/camera': 0, '/fast': 0}
    start = time.monotonic()
    while (now := time.monotonic() - start) < seconds:
        while sent['/fast'] < now * 1000:
            fast.publish(Int64(data=sent['/fast']))
            sent['/fast'] += 1
        if sent['/camera'] < now * 30:
            camera.publish(image)
            sent['/camera'] += 1
        time.sleep(0.0005)
    print(sent['/camera'], sent['/fast'], flush=True)
    # The last reliable messages are still being delivered: up to 1 s until every reader has them.
    deadline = time.monotonic() + 1.0
    for publisher in (camera, fast):
        publisher.wait_for_all_acked(Duration(nanoseconds=int(max(0.0, deadline - time.monotonic()) * 1e9)))
    node.destroy_node()
    rclpy.shutdown()
''')


BASELINE = textwrap.dedent('''
    import sys
    import rclpy
    from rclpy.qos import QoSProfile
    from sensor_msgs.msg import Image
    from std_msgs.msg import Int64

    rclpy.init()
    node = rclpy.create_node('bag_bench_baseline')
    counts = {'/camera': 0, '/fast': 0}
    def counter(topic):
        def count(_message):
            counts[topic] += 1
        return count
    node.create_subscription(Image, '/camera', counter('/camera'), QoSProfile(depth=1000), raw=True)
    node.create_subscription(Int64, '/fast', counter('/fast'), QoSProfile(depth=1000), raw=True)
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        print(counts['/camera'], counts['/fast'], flush=True)
''')


def publish(sandbox: RosSandbox, seconds: float) -> dict[str, int]:
    """Run the publisher until it has sent for that long (once one subscriber matched); what it sent."""
    result = subprocess.run([sys.executable, '-c', PUBLISHER, str(seconds), '1'], env=sandbox.env,
                            capture_output=True, text=True, timeout=seconds + 60, check=True)
    time.sleep(1.0)  # what is still in flight arrives
    return dict(zip(TOPICS, map(int, result.stdout.split()), strict=True))


def main() -> int:
    """Run the baseline, then the recorder, against the same publisher; print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--seconds', type=float, default=10.0, help='how long the publisher sends')
    args = parser.parse_args()
    with RosSandbox() as sandbox, tempfile.TemporaryDirectory() as folder:
        # The subscriber first each time: the recorder finds named topics once they are in the graph,
        # so the publisher waits for one matched subscription, then sends.
        baseline = sandbox.command([sys.executable, '-c', BASELINE], label='baseline')
        baseline_sent = publish(sandbox, args.seconds)
        baseline.send_signal(signal.SIGINT)
        baseline.wait(10)
        received = dict(zip(TOPICS, map(int, baseline.output.split()[-2:]), strict=True))
        bag = Path(folder) / 'bench'
        recorder = sandbox.command(['ros2', 'bag', 'record', '-o', str(bag), *TOPICS], label='record')
        recorder_sent = publish(sandbox, args.seconds)
        recorder.stop_cleanly(timeout=10)
        info = yaml.safe_load((bag / 'metadata.yaml').read_text())['rosbag2_bagfile_information']
        written = {t['topic_metadata']['name']: t['message_count'] for t in info['topics_with_message_count']}
        size = sum(p.stat().st_size for p in bag.iterdir())
    print(f'{args.seconds:g} s of a 30 fps 640x480 rgb8 camera and a 1 kHz Int64; '
          f'bag {size / 2**20:.1f} MiB')
    print(f"{'topic':10} {'baseline sent/got':>18} {'recorder sent/wrote':>20} {'written share':>14} "
          f"{'ratio':>6}")
    for topic in TOPICS:
        base = received[topic] / baseline_sent[topic]
        share = written.get(topic, 0) / recorder_sent[topic]
        # A baseline that got nothing (once, a 1 s run in a loaded test suite) gives no ratio.
        ratio = f'{share / base:6.2f}' if base else f"{'n/a':>6}"
        print(f'{topic:10} {baseline_sent[topic]:8d}/{received[topic]:<9d} {recorder_sent[topic]:9d}/'
              f'{written.get(topic, 0):<10d} {share:14.3f} {ratio}')
    if not all(received.values()):
        print('the baseline received none of a topic: the machine was too busy for this measurement')
    return 0


if __name__ == '__main__':
    sys.exit(main())
