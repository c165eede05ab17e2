"""`ros2 doctor hello`: whether the hosts that run it hear each other, over ROS and UDP multicast.

Each host publishes `hello, it's me <hostname>` on a topic and sends the same text to a multicast
group, and counts, per other host, what it hears back; the counts are printed as a table every
print period.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import socket
import sys
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

from ros2doctor.verb import VerbExtension

if TYPE_CHECKING:  # rclpy is imported when the verb runs: `ros2 doctor -h` imports this module
    from rclpy.executors import Executor
    from rclpy.node import Node

DEFAULT_GROUP = '225.0.0.1'
DEFAULT_PORT = 49150
DEFAULT_TOPIC = '/canyouhearme'
MAX_TTL = 255  # the IP header's TTL is one byte
RECEIVE_POLL = 0.2  # how soon the receiving thread notices that it is to stop

Number = TypeVar('Number', int, float)


def positive(type_: type[Number]) -> Callable[[str], Number]:
    """An argparse type: the text as type_ (int or float), ArgumentTypeError unless finite and above zero."""
    def convert(text: str) -> Number:
        message = f'value must be a positive {type_.__name__}'
        try:
            value = type_(text)
        except ValueError:
            raise argparse.ArgumentTypeError(message) from None
        if not (value > 0 and math.isfinite(value)):
            raise argparse.ArgumentTypeError(message)
        return value
    return convert


positive_float = positive(float)
positive_int = positive(int)


def multicast_ttl(text: str) -> int:
    """An argparse type: a positive int that fits the IP header's TTL."""
    value = positive_int(text)
    if value > MAX_TTL:
        raise argparse.ArgumentTypeError(f'value must be at most {MAX_TTL}')
    return value


def node_name_prefix(hostname: str, pid: int) -> str:
    """`ros2doctor_<hostname>_<pid>`, with each character a node name cannot hold turned into `_`."""
    return f"ros2doctor_{re.sub(r'[^0-9a-zA-Z_]', '_', hostname)}_{pid}"


NODE_NAME_PREFIX = node_name_prefix(socket.gethostname(), os.getpid())


def hello_payload(hostname: str) -> str:
    """What a host publishes and sends: the same text over ROS and over multicast."""
    return f"hello, it's me {hostname}"


def remote_sender(payload: str, local_hostname: str) -> str | None:
    """The hostname a hello ends with, or None when it is this host's own (or has no words at all)."""
    words = payload.split()
    if not words or words[-1] == local_hostname:
        return None
    return words[-1]


def _row(hostname: object, count: object) -> str:
    return f'{"":15} {hostname!s:<20} {count!s:<10}'


class SummaryTable:
    """Counts of hellos published and sent here, and heard per other host; shared by threads.

    `lock` is reentrant, so that a caller can print and reset under it without losing a count.
    """

    def __init__(self) -> None:
        self.lock = threading.RLock()
        self._pub = 0
        self._send = 0
        self._sub: dict[str, int] = {}
        self._receive: dict[str, int] = {}

    def reset(self) -> None:
        """Start counting from zero, as after each printed table."""
        with self.lock:
            self._pub = 0
            self._send = 0
            self._sub = {}
            self._receive = {}

    def increment_pub(self) -> None:
        """Count one hello published on the topic."""
        with self.lock:
            self._pub += 1

    def increment_sub(self, hostname: str) -> None:
        """Count one hello from that host heard on the topic."""
        with self.lock:
            self._sub[hostname] = self._sub.get(hostname, 0) + 1

    def increment_send(self) -> None:
        """Count one hello sent to the multicast group."""
        with self.lock:
            self._send += 1

    def increment_receive(self, hostname: str) -> None:
        """Count one hello from that host received from the multicast group."""
        with self.lock:
            self._receive[hostname] = self._receive.get(hostname, 0) + 1

    def format_summary(self, topic: str, print_period: float, *, group: str = DEFAULT_GROUP,
                       port: int = DEFAULT_PORT) -> str:
        """The table, in upstream's layout: the ROS counts, the multicast counts, a rule of dashes."""
        def hosts(counts: dict[str, int]) -> list[str]:
            return [_row('Hostname', f'Msg Count /{print_period}s'),
                    *(_row(hostname, count) for hostname, count in counts.items())]

        with self.lock:
            lines = ['MULTIMACHINE COMMUNICATION SUMMARY',
                     f'Topic: {topic}, Published Msg Count: {self._pub}',
                     'Subscribed from:', *hosts(self._sub),
                     f'Multicast Group/Port: {group}/{port}, Sent Msg Count: {self._send}',
                     'Received from:', *hosts(self._receive),
                     '-' * 60]
        return '\n'.join(lines)

    def format_print_summary(self, topic: str, print_period: float, *, group: str = DEFAULT_GROUP,
                             port: int = DEFAULT_PORT) -> None:
        """Print the table (see format_summary)."""
        print(self.format_summary(topic, print_period, group=group, port=port))


class HelloPublisher:
    """Publishes this host's hello as std_msgs/String on the topic."""

    def __init__(self, node: Node, topic: str, summary_table: SummaryTable, *, qos: Any = None) -> None:
        # Lazy: rclpy and the message package are slow to import (see TYPE_CHECKING above).
        from rclpy.qos import qos_profile_system_default
        from std_msgs.msg import String

        self._message = String(data=hello_payload(socket.gethostname()))
        self._summary_table = summary_table
        profile = qos if qos is not None else qos_profile_system_default
        self._pub = node.create_publisher(String, topic, profile)

    def destroy(self) -> None:
        """Remove the publisher from its node."""
        self._pub.destroy()

    def publish(self) -> None:
        """Publish one hello."""
        self._summary_table.increment_pub()
        self._pub.publish(self._message)


class HelloSubscriber:
    """Counts the hellos of other hosts heard on the topic."""

    def __init__(self, node: Node, topic: str, summary_table: SummaryTable, *, qos: Any = None) -> None:
        from rclpy.qos import qos_profile_system_default
        from std_msgs.msg import String

        self._hostname = socket.gethostname()
        self._summary_table = summary_table
        profile = qos if qos is not None else qos_profile_system_default
        self._sub = node.create_subscription(String, topic, self._callback, profile)

    def destroy(self) -> None:
        """Remove the subscription from its node."""
        self._sub.destroy()

    def _callback(self, message: Any) -> None:
        sender = remote_sender(message.data, self._hostname)
        if sender is not None:
            self._summary_table.increment_sub(sender)


class HelloMulticastUDPSender:
    """Sends this host's hello to the multicast group; send() raises OSError where the network refuses."""

    def __init__(self, summary_table: SummaryTable, group: str = DEFAULT_GROUP, port: int = DEFAULT_PORT,
                 ttl: int | None = None) -> None:
        self._socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
        try:
            if ttl is not None:
                self._socket.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, ttl)
        except OSError:
            self._socket.close()
            raise
        self._payload = hello_payload(socket.gethostname()).encode()
        self._summary_table = summary_table
        self._destination = (group, port)

    def send(self) -> None:
        """Send one hello (counted once it has left)."""
        self._socket.sendto(self._payload, self._destination)
        self._summary_table.increment_send()

    def shutdown(self) -> None:
        """Close the socket."""
        self._socket.close()


class HelloMulticastUDPReceiver:
    """Counts the hellos of other hosts received from the multicast group, in recv() (run it in a thread).

    Several of these, in one process or many, share the port (SO_REUSEADDR/SO_REUSEPORT): each gets
    every datagram. With a timeout, recv() ends once that long has passed without a datagram.
    """

    def __init__(self, summary_table: SummaryTable, group: str = DEFAULT_GROUP, port: int = DEFAULT_PORT,
                 timeout: float | None = None) -> None:
        self._socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
        try:
            self._socket.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            if hasattr(socket, 'SO_REUSEPORT'):  # not on Windows
                self._socket.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEPORT, 1)
            self._socket.bind(('', port))
            # struct ip_mreq: the group, joined on the default interface
            membership = socket.inet_aton(group) + socket.inet_aton('0.0.0.0')
            self._socket.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, membership)
            self._socket.settimeout(RECEIVE_POLL)
        except OSError:
            self._socket.close()
            raise
        self._hostname = socket.gethostname()
        self._summary_table = summary_table
        self._timeout = timeout
        self._stopping = threading.Event()

    def recv(self) -> None:
        """Receive and count until shutdown() (or the timeout), then close the socket.

        A socket error ends it with one line on stderr.
        """
        last_heard = time.monotonic()
        try:
            while not self._stopping.is_set():
                if self._timeout is not None and time.monotonic() - last_heard > self._timeout:
                    return
                try:
                    data, _ = self._socket.recvfrom(4096)
                except TimeoutError:
                    continue
                except OSError as error:
                    say_multicast_off('receive', error)
                    return
                last_heard = time.monotonic()
                try:
                    sender = remote_sender(data.decode(), self._hostname)
                except UnicodeDecodeError:  # not a hello: someone else's traffic on the group
                    continue
                if sender is not None:
                    self._summary_table.increment_receive(sender)
        finally:
            self._socket.close()

    def shutdown(self) -> None:
        """Make recv() return, within RECEIVE_POLL."""
        self._stopping.set()


_multicast_off_said = threading.Event()


def say_multicast_off(what: str, error: OSError) -> None:
    """One line on stderr, the first time only: multicast does not work here, the ROS part goes on.

    A later failure (the other direction) adds nothing the table's zero counts do not show.
    """
    if _multicast_off_said.is_set():
        return
    _multicast_off_said.set()
    print(f'ros2 doctor hello: UDP multicast on {DEFAULT_GROUP}/{DEFAULT_PORT} does not work here '
          f'(cannot {what}: {error}); the ROS topic part goes on', file=sys.stderr)


class HelloVerb(VerbExtension):
    """Check network connectivity between multiple hosts.

    Run it on each host: every host publishes a hello on a ROS topic and sends one to a UDP multicast
    group each emit period, and prints, every print period, a table of what it heard from which other
    host over each.
    """

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """-t/--topic, -ep/--emit-period, -pp/--print-period, --ttl, -1/--once."""
        parser.add_argument('-t', '--topic', nargs='?', default=DEFAULT_TOPIC, const=DEFAULT_TOPIC,
                            help=f"Name of ROS topic to publish to (default: '{DEFAULT_TOPIC}')")
        parser.add_argument('-ep', '--emit-period', metavar='N', type=positive_float, default=0.1,
                            help='Time period to publish/send one message (default: 0.1s)')
        parser.add_argument('-pp', '--print-period', metavar='N', type=positive_float, default=1.0,
                            help='Time period to print summary table (default: 1.0s)')
        parser.add_argument('--ttl', type=multicast_ttl, help='TTL for multicast send (default: None)')
        parser.add_argument('-1', '--once', action='store_true',
                            help='Publish and multicast send for one emit period then exit; '
                                 'used in test case.')

    def main(self, *, args: argparse.Namespace, summary_table: SummaryTable | None = None) -> int:
        """Say hello and print the table until Ctrl-C (or once, after one emit period, with --once).

        Multicast that this machine cannot do is said in one line on stderr; the ROS half goes on.
        """
        # Lazy: rclpy is slow to import, and `ros2 doctor -h` imports this module.
        from rclpy.executors import SingleThreadedExecutor
        from ros2cli.node.direct import DirectNode

        table = summary_table if summary_table is not None else SummaryTable()
        # No wait for discovery: the other hosts are counted whenever they turn up.
        with DirectNode(args, node_name=NODE_NAME_PREFIX + '_node', spin_time=0.0) as direct:
            publisher = HelloPublisher(direct.node, args.topic, table)
            HelloSubscriber(direct.node, args.topic, table)  # its node keeps it
            sender = _multicast_part('send', lambda: HelloMulticastUDPSender(table, ttl=args.ttl))
            receiver = _multicast_part('receive', lambda: HelloMulticastUDPReceiver(table))
            receiving = None
            if receiver is not None:
                receiving = threading.Thread(target=receiver.recv, name='hello receiver', daemon=True)
                receiving.start()
            executor = SingleThreadedExecutor(context=direct.node.context)
            executor.add_node(direct.node)
            try:
                _emit_until_done(executor, publisher, sender, table, args)
            except KeyboardInterrupt:
                pass  # Ctrl-C is how hello ends: exit code 0, as upstream's
            finally:
                executor.remove_node(direct.node)
                if sender is not None:
                    sender.shutdown()
                if receiver is not None and receiving is not None:
                    receiver.shutdown()
                    receiving.join()
        return 0


PartT = TypeVar('PartT')


def _multicast_part(what: str, make: Callable[[], PartT]) -> PartT | None:
    """make(), or None after saying why, when this machine refuses the multicast socket."""
    try:
        return make()
    except OSError as error:
        say_multicast_off(what, error)
        return None


def _emit_until_done(executor: Executor, publisher: HelloPublisher, sender: HelloMulticastUDPSender | None,
                     table: SummaryTable, args: argparse.Namespace) -> None:
    """Say hello each emit period, serving the subscription in between; print the table as asked."""
    last_print = next_emit = time.monotonic()
    while True:
        if time.monotonic() - last_print > args.print_period:
            with table.lock:  # what arrives between printing and resetting is counted in the next table
                table.format_print_summary(args.topic, args.print_period)
                table.reset()
            last_print = time.monotonic()
        publisher.publish()
        if sender is not None:
            try:
                sender.send()
            except OSError as error:  # e.g. no route to the group: stop trying, keep the ROS half
                say_multicast_off('send', error)
                sender.shutdown()
                sender = None
        next_emit += args.emit_period
        if next_emit < time.monotonic():  # fell behind (a slow print): start the period afresh
            next_emit = time.monotonic() + args.emit_period
        while (left := next_emit - time.monotonic()) > 0:
            executor.spin_once(timeout_sec=left)
        if args.once:
            table.format_print_summary(args.topic, args.print_period)
            return
