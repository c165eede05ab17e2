"""One service call with patience: wait for the server, send, resend when the answer is lost.

A response can be lost when the server has not yet matched a fresh client's response reader
(a new participant, a loaded machine). The callers here send idempotent requests (parameter
services), so the remedy is to ask again. Used by `ros2 param` directly and by the daemon,
which makes the calls for a verb from its warm node.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # rclpy is imported where it is used: the daemon's client side never needs it
    from rclpy.client import Client
    from rclpy.node import Node

CALL_ATTEMPTS = 3


class ServiceCallError(RuntimeError):
    """A call that did not produce a response; str() says why."""


class ServiceUnavailable(ServiceCallError):
    """No server of the service showed up within the timeout."""

    pass


class NoResponse(ServiceCallError):
    """No response came to any of the CALL_ATTEMPTS sends of the request."""

    pass


class ServiceCaller:
    """Calls services from one rclpy node, keeping a client per service for later calls."""

    def __init__(self, node: Node) -> None:
        self._node = node
        # srv_class: the generated service class, found by its name at run time
        self._clients: dict[tuple[str, Any], Client] = {}

    def call(self, service: str, srv_class: Any, request: Any, timeout: float) -> Any:
        """The service's response to request; ServiceCallError (or a subclass) when there is none.

        It waits up to timeout s for the server, then sends the request up to CALL_ATTEMPTS times, each
        attempt waiting longer for the answer (timeout * attempt / CALL_ATTEMPTS s).
        """
        import rclpy  # lazy: slow to import, and `ros2 param -h` imports this module (ros2cli.api.param)

        client = self._clients.get((service, srv_class))
        if client is None:
            client = self._clients[(service, srv_class)] = self._node.create_client(srv_class, service)
        if not client.wait_for_service(timeout_sec=timeout):
            raise ServiceUnavailable(f'service {service} is not available')
        for attempt in range(1, CALL_ATTEMPTS + 1):
            future = client.call_async(request)
            wait = timeout * attempt / CALL_ATTEMPTS
            rclpy.spin_until_future_complete(self._node, future, timeout_sec=wait)
            if future.done():
                break
            client.remove_pending_request(future)
        if not future.done():
            raise NoResponse(f'no response from {service}')
        if future.exception() is not None:
            raise ServiceCallError(f'{future.exception()!r}')
        return future.result()


# fault codes of the daemon's call_service
FAULTS: dict[int, type[ServiceCallError]] = {1: ServiceUnavailable, 2: NoResponse, 3: ServiceCallError}


class DaemonServiceCaller:
    """The same calls, made by the daemon's node (already discovered by everyone)."""

    def __init__(self, timeout: float) -> None:
        # Lazy: `ros2 param -h` imports this module.
        from ros2cli.daemon.client import DaemonGraph
        self._daemon = DaemonGraph(timeout=timeout * 2 + 5.0)

    def call(self, service: str, srv_class: Any, request: Any, timeout: float) -> Any:
        """The same call, made by the daemon (see serve_call): the same response, or the same exceptions."""
        # Lazy: rosidl_runtime_py (yaml) imports slowly; `ros2 param -h` imports this module.
        from rosidl_runtime_py.convert import dump_yaml, message_to_ordereddict
        from rosidl_runtime_py.set_message import parse_yaml, set_message_fields
        from rosidl_runtime_py.utilities import type_name_of

        from ros2cli.daemon.client import DaemonFault

        try:
            text = self._daemon.call_service(service, type_name_of(srv_class),
                                             dump_yaml(message_to_ordereddict(request)), timeout)
        except DaemonFault as fault:
            raise FAULTS.get(fault.code, ServiceCallError)(fault.message) from None
        response = srv_class.Response()
        set_message_fields(response, parse_yaml(text))
        return response


def serve_call(caller: ServiceCaller, service: str, type_name: str, request_yaml: str, timeout: float) -> str:
    """The daemon's side of DaemonServiceCaller.call.

    Requests and responses travel as YAML text of the codec: plain data for XML-RPC (which has
    no 64-bit integers), and the client needs no rclpy import for it, which keeps warm calls fast.
    """
    # Lazy: xmlrpc.client and rosidl_runtime_py (yaml) import slowly; `ros2 param -h` imports this module.
    import xmlrpc.client  # the daemon's fault, which it passes on over XML-RPC and JSON alike

    from rosidl_runtime_py.convert import dump_yaml, message_to_ordereddict
    from rosidl_runtime_py.set_message import FieldError, parse_yaml, set_message_fields
    from rosidl_runtime_py.utilities import InvalidType, import_type

    try:
        srv_class = import_type(type_name, 'srv')
        request = srv_class.Request()
        set_message_fields(request, parse_yaml(request_yaml))
    except (InvalidType, FieldError) as error:
        raise xmlrpc.client.Fault(3, str(error)) from None
    try:
        response = caller.call(service, srv_class, request, timeout)
    except ServiceCallError as error:
        code = next(c for c, kind in FAULTS.items() if isinstance(error, kind))
        raise xmlrpc.client.Fault(code, str(error)) from None
    return dump_yaml(message_to_ordereddict(response))
