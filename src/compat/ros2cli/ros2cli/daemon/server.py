"""The daemon process: a hidden node whose graph cache stays warm, served over XML-RPC and JSON.

Started by ros2cli.daemon.client.spawn_daemon() with the already bound listening socket.
"""

import argparse
import hashlib
import json
import os
import socket
import time
import uuid
import xmlrpc.client
from typing import Any
from xmlrpc.server import SimpleXMLRPCRequestHandler, SimpleXMLRPCServer

import rclpy
from owl_common.graph import GraphQueries
from rclpy.node import Node

from ros2cli.daemon import JSON_PATH, RPC_PATH, daemon_port
from ros2cli.node.direct import tear_down
from ros2cli.node.graph import Graph
from ros2cli.node.settle import graph_endpoints, graph_view, local_participants
from ros2cli.service_call import ServiceCaller, serve_call

IDLE_TIMEOUT = 2 * 60 * 60.0  # seconds without a request, as upstream
# A daemon that a verb started on its own (not `ros2 daemon start`) also leaves once no other
# node has had an endpoint in its domain for this long: the nodes it served are gone (a test
# ended, the user stopped everything), and a forgotten daemon per domain would pile up.
# ROS2CLI_DAEMON_ALONE_TIMEOUT (seconds) overrides it.
ALONE_TIMEOUT = 60.0


def keeps_company(graph: Graph) -> bool:
    """Whether a node other than `ros2`'s own has a publisher or subscription in the graph.

    Endpoints, not node names: a node can stay listed after its process is gone. rmw_dds_common
    adds a participant back when one of its ros_discovery_info samples is handled after the
    participant was removed (the ghost nodes of upstream ros2/ros2#514), but its endpoints leave
    with it for good. Every rclpy and rclcpp node publishes /rosout and /parameter_events.
    """
    return any(not info['node_name'].startswith('_ros2cli') for info in graph_endpoints(graph))


class _RequestHandler(SimpleXMLRPCRequestHandler):
    rpc_paths = (RPC_PATH, JSON_PATH)

    def do_POST(self) -> None:
        """XML-RPC at RPC_PATH, as upstream's daemon; the same calls as JSON at JSON_PATH (our client's)."""
        if self.path != JSON_PATH:
            super().do_POST()
            return
        try:
            length = int(self.headers.get('content-length', 0))
            if length < 0:  # read(-1) would wait for the client to close
                raise ValueError(length)
            request = json.loads(self.rfile.read(length))
            method, params = request['method'], request['params']
            if not isinstance(method, str) or not isinstance(params, list):
                raise TypeError
        except (ValueError, KeyError, TypeError):
            self.send_error(400, 'expected a JSON object {"method": name, "params": [...]}')
            return
        try:
            body = json.dumps({'result': self.server._dispatch(method, params)})  # type: ignore[attr-defined]
        except xmlrpc.client.Fault as fault:
            body = json.dumps({'fault': [fault.faultCode, fault.faultString]})
        except Exception as error:  # reported to the caller, as SimpleXMLRPCServer reports it: code 1
            body = json.dumps({'fault': [1, f'{type(error).__name__}: {error}']})
        answer = body.encode()
        self.send_response(200)
        self.send_header('Content-Type', 'application/json')
        self.send_header('Content-Length', str(len(answer)))
        self.end_headers()
        self.wfile.write(answer)


class _Server(SimpleXMLRPCServer):
    timed_out = False

    def handle_timeout(self) -> None:
        self.timed_out = True


def serve(domain: int, listener: socket.socket, idle_timeout: float, alone_timeout: float | None) -> None:
    """Answer XML-RPC and JSON calls on listener from a hidden node in the domain, until it is time to stop.

    That is on system.shutdown (`ros2 daemon stop`), after idle_timeout s without a request, or, when
    alone_timeout is not None, once no node but `ros2`'s own has kept it company (keeps_company)
    for that long.
    """
    server = _Server(
        ('127.0.0.1', daemon_port(domain)), requestHandler=_RequestHandler, logRequests=False,
        allow_none=True, bind_and_activate=False)
    server.socket.close()
    server.socket = listener
    server.timeout = 1.0

    rclpy.init(args=[], domain_id=domain)
    node = Node(f'_ros2cli_daemon_{domain}_{uuid.uuid4().hex}', start_parameter_services=False)
    stopping: list[bool] = []
    server.register_introspection_functions()
    server.register_instance(GraphQueries(node))
    server.register_function(node.get_name, 'get_name')
    server.register_function(node.get_namespace, 'get_namespace')
    started = time.monotonic()
    server.register_function(lambda: domain, 'get_domain_id')
    server.register_function(lambda: time.monotonic() - started, 'get_uptime')
    graph = GraphQueries(node)

    def discovery_view() -> list[Any]:
        """What ros2cli.node.settle needs of this daemon's graph, in one call: [digest, others, complete].

        The graph is reduced to a digest (SHA-1 of its repr): XML-RPC carries no tuples.
        """
        seen, others, complete = graph_view(graph, local_participants())
        return [hashlib.sha1(repr(seen).encode()).hexdigest(), others, complete]
    server.register_function(discovery_view, 'discovery_view')
    caller = ServiceCaller(node)
    server.register_function(
        lambda service, type_name, text, timeout: serve_call(caller, service, type_name, text, timeout),
        'call_service')

    def shutdown() -> bool:
        stopping.append(True)
        return True
    server.register_function(shutdown, 'system.shutdown')

    last_request = last_company = time.monotonic()
    try:
        while not stopping and time.monotonic() - last_request < idle_timeout:
            server.timed_out = False
            server.handle_request()
            now = time.monotonic()
            if not server.timed_out:
                last_request = now
            if alone_timeout is not None:
                if keeps_company(graph):
                    last_company = now
                elif now - last_company > alone_timeout:
                    break
    finally:
        # The port closes last: `ros2 daemon stop` returns when it is free, and a daemon started
        # next must not find this one's participant still in the graph (it would count it as one
        # of the domain's participants, then miss another's node when this one's port went).
        try:
            tear_down(node)
        finally:
            server.server_close()


def main() -> None:
    """The daemon process's entry point: the options spawn_daemon() passes, then serve(); Ctrl-C ends it."""
    parser = argparse.ArgumentParser(prog='ros2-daemon')
    parser.add_argument('--ros-domain-id', type=int, required=True)
    parser.add_argument('--fd', type=int, required=True, help='the bound, listening socket')
    parser.add_argument('--idle-timeout', type=float, default=IDLE_TIMEOUT)
    parser.add_argument('--exit-when-alone', action='store_true',
                        help=f'also exit after {ALONE_TIMEOUT:.0f} s with no other node in the domain')
    args = parser.parse_args()
    os.environ['ROS_DOMAIN_ID'] = str(args.ros_domain_id)
    listener = socket.socket(fileno=args.fd)
    try:
        alone_timeout = float(os.environ.get('ROS2CLI_DAEMON_ALONE_TIMEOUT', ALONE_TIMEOUT)) \
            if args.exit_when_alone else None
        serve(args.ros_domain_id, listener, args.idle_timeout, alone_timeout)
    except KeyboardInterrupt:
        pass


if __name__ == '__main__':
    main()
