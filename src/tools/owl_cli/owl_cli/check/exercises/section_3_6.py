"""Section 3.6: services (the course's temperature conversion, then currency or factorial)."""

from __future__ import annotations

import math
from typing import Any

from rosidl_runtime_py.utilities import get_service

from owl_cli.check import criteria as judge
from owl_cli.check import workspace as ws
from owl_cli.check.catalogue import TERMINAL, Section
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    PROBE_NODE,
    START_TIMEOUT,
    Session,
    client_ended,
    workspace,
)

SECTION = Section()


SECTION.by_hand(
    'turtle_services',
    '3.6.1 exercises',
    'turtlesim',
    "spawn, kill and teleport turtlesim's turtles with ros2 service call and rqt's Service Caller",
    TERMINAL,
)


@SECTION.check(
    'temp_server',
    '3.6.3',
    'olive_srvcli',
    'the temp_conversion service (olive_interfaces/srv/TempConv): Celsius to Kelvin and Fahrenheit',
)
def check_temp_server(s: Session) -> None:
    """Run temp_server: it offers temp_conversion (TempConv) and answers 0 and 100 °C by formulas (1), (2)."""
    from olive_interfaces.srv import TempConv

    s.student('olive_srvcli', 'temp_server')
    s.wait(
        lambda: any(name == '/temp_conversion' for name, _ in s.node.get_service_names_and_types()),
        START_TIMEOUT,
    )
    types = dict(s.node.get_service_names_and_types()).get('/temp_conversion')
    if not s.add(
        Criterion(
            'offers the service temp_conversion of type olive_interfaces/srv/TempConv',
            types == ['olive_interfaces/srv/TempConv'],
            "create_service(TempConv, 'temp_conversion', callback)"
            if types is None
            else f'its type is {types}',
        )
    ):
        s.stop_student()
        return
    for temp_c in (0.0, 100.0):
        response = s.call(TempConv, '/temp_conversion', TempConv.Request(temp_c=temp_c))
        if response is None:
            s.add(
                Criterion(
                    f'temp_conversion answers {temp_c:g} °C',
                    False,
                    'no answer in 10 s: the callback must return the response',
                )
            )
            continue
        s.add(judge.kelvin(temp_c, response.temp_k))
        s.add(judge.fahrenheit(temp_c, response.temp_f))
    s.stop_student()


@SECTION.check(
    'temp_client',
    '3.6.3',
    'olive_srvcli',
    'sends its command-line Celsius value to temp_conversion and prints the answer',
)
def check_temp_client(s: Session) -> None:
    """Run `temp_client 100` against the check's own server: it asks for 100.0, prints the answer, ends."""
    from olive_interfaces.srv import TempConv

    requests = []

    def answer(request: Any, response: Any) -> Any:
        requests.append(request.temp_c)
        response.temp_k = request.temp_c + 273.15
        response.temp_f = request.temp_c * 9 / 5 + 32
        return response

    s.node.create_service(TempConv, '/temp_conversion', answer)
    process = s.student('olive_srvcli', 'temp_client', '100')
    s.wait(lambda: not process.running(), 15.0)
    s.add(
        Criterion(
            'sends the command-line value as temp_c (temp_client 100 asks for 100.0)',
            100.0 in requests,
            "float(sys.argv[1]) goes into the request's temp_c",
            f'requests {requests}',
        )
    )
    s.add(
        Criterion(
            "prints the server's answer (373.15 Kelvin and 212.0 Fahrenheit)",
            '373.15' in process.output and '212.0' in process.output,
            'log response.temp_k and response.temp_f',
            judge.tail_lines(process.output, 1),
        )
    )
    client_ended(s, process)


# Services every node offers (parameters, type description), never the exercise's own.
STANDARD_SERVICE_SUFFIXES = (
    '/describe_parameters',
    '/get_parameter_types',
    '/get_parameters',
    '/list_parameters',
    '/set_parameters',
    '/set_parameters_atomically',
    '/get_type_description',
)


REFERENCE = {
    'currency': (
        "the reference solution's currency_server offers currency_conversion "
        '(olive_interfaces/srv/CurrencyConv: float64 euros -> float64 dollars, pounds, swiss_francs)'
    ),
    'factorial': (
        "the reference solution's factorial_server offers factorial "
        '(olive_interfaces/srv/Factorial: int64 n -> uint64 factorial)'
    ),
}


FLOAT_TYPES = ('double', 'float')


INTEGER_TYPES = ('int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32', 'int64', 'uint64')


def own_service(name: str) -> bool:
    """Whether a service is one a node made itself, not one rclpy gives every node or an action's."""
    return not name.endswith(STANDARD_SERVICE_SUFFIXES) and '/_action/' not in name


def fields(message: Any, kinds: tuple[str, ...]) -> list[str]:
    """The names of the message's fields whose type is one of kinds ('double', 'int64', ...), in order."""
    return [name for name, kind in message.get_fields_and_field_types().items() if kind in kinds]


def find_student_executable(s: Session, subject: str, role: str) -> tuple[str, str] | None:
    """(package, executable) of the workspace for the exercise, olive_srvcli (the course's) first."""
    names = sorted(ws.packages(workspace()), key=lambda name: name != 'olive_srvcli')
    for package in names:
        executable = ws.find_executable(ws.executables(workspace(), package), subject, role)
        if executable:
            return package, executable
    s.add(
        Criterion(
            f'the workspace has a {subject} {role} executable',
            False,
            f"no executable with '{subject}' and '{role}' in its name in the workspace's packages "
            f'({REFERENCE[subject]}; its executable is {subject}_{role})',
        )
    )
    return None


def check_service_server(s: Session, subject: str) -> None:
    """Check the student's server for subject ('currency' or 'factorial') through its own service type.

    The service and its type are whatever the executable offers (the course leaves them to the
    student): the first number field of the request carries the question, every number field of
    the response is read as the answer.
    """
    found = find_student_executable(s, subject, 'server')
    if found is None:
        return
    s.student(*found)

    def services() -> list[tuple[str, str]]:
        return [
            (name, types[0])
            for name, types in s.node.get_service_names_and_types()
            if own_service(name) and types and not name.startswith(f'/{PROBE_NODE}/')
        ]

    s.wait(lambda: bool(services()), START_TIMEOUT)
    offered = sorted(services(), key=lambda item: subject[:4] not in (item[0] + item[1]).lower())
    if not s.add(
        Criterion(
            f'{found[1]} offers a service',
            bool(offered),
            f'no service appeared: create_service(YourType, name, callback) ({REFERENCE[subject]})',
            ', '.join(f'{name} ({kind})' for name, kind in offered),
        )
    ):
        s.stop_student()
        return
    name, type_name = offered[0]
    srv = get_service(type_name)  # the student's workspace is sourced: its types import
    number_fields = fields(srv.Request(), FLOAT_TYPES + INTEGER_TYPES)
    if not s.add(
        Criterion(
            f"{type_name}'s request has a number field",
            bool(number_fields),
            f'the request must carry the {"euros" if subject == "currency" else "integer"} '
            f'({REFERENCE[subject]})',
            ', '.join(srv.Request().get_fields_and_field_types()),
        )
    ):
        s.stop_student()
        return
    field = number_fields[0]
    integer = srv.Request().get_fields_and_field_types()[field] in INTEGER_TYPES

    def ask(value: float) -> Any | None:
        request = srv.Request()
        setattr(request, field, int(value) if integer else float(value))
        response = s.call(srv, name, request)
        if response is None:
            s.add(
                Criterion(
                    f'{name} answers {value:g}',
                    False,
                    'no answer in 10 s: the callback must return the response',
                )
            )
        return response

    if subject == 'currency':
        answers = {euros: ask(euros) for euros in (100, 250)}
        if None not in answers.values():
            amounts = {
                euros: [float(getattr(r, f)) for f in fields(r, FLOAT_TYPES + INTEGER_TYPES)]
                for euros, r in answers.items()
            }
            for criterion in judge.currency_answers(amounts[100], amounts[250]):
                s.add(criterion)
    else:
        for n in (5, 0, 10):
            response = ask(n)
            if response is not None:
                values = [getattr(response, f) for f in fields(response, FLOAT_TYPES + INTEGER_TYPES)]
                s.add(judge.factorial_answer(n, values))
    s.stop_student()


@SECTION.check(
    'currency_server',
    '3.6 exercise',
    'olive_srvcli',
    'a service that converts euros into three currencies (choose it or factorial)',
    choice='3.6',
)
def check_currency_server(s: Session) -> None:
    """Check the currency server: three amounts for 100 euros, 2.5 times as much for 250, three rates."""
    check_service_server(s, 'currency')


CLIENT_ARGUMENT = {'currency': 100, 'factorial': 5}


RATES = (1.25, 0.75, 1.5)  # the check's own server: different units per euro for each field


def check_service_client(s: Session, subject: str) -> None:
    """Check the student's client for subject ('currency' or 'factorial') against the check's own server.

    The client runs with CLIENT_ARGUMENT; the check serves the service and type the client asks for,
    answers with RATES (currency) or the factorial, and looks for the answer in the client's output.
    """
    found = find_student_executable(s, subject, 'client')
    if found is None:
        return
    argument = CLIENT_ARGUMENT[subject]
    process = s.student(*found, str(argument))

    def clients() -> list[tuple[str, str]]:
        found_clients = []
        for node, namespace in s.node.get_node_names_and_namespaces():
            if node == PROBE_NODE or node.startswith(('olive_', '_')):
                continue
            try:
                pairs = s.node.get_client_names_and_types_by_node(node, namespace)
            except Exception:  # the node left the graph between the two calls
                continue
            found_clients += [(name, types[0]) for name, types in pairs if own_service(name) and types]
        return found_clients

    s.wait(lambda: bool(clients()), START_TIMEOUT)
    seen = clients()
    if not s.add(
        Criterion(
            f'{found[1]} {argument} creates a service client',
            bool(seen),
            f'no client appeared: create_client(YourType, name) ({REFERENCE[subject]})',
            ', '.join(f'{name} ({kind})' for name, kind in seen),
        )
    ):
        if process.running():
            s.stop_student()
        return
    name, type_name = seen[0]
    srv = get_service(type_name)  # the student's workspace is sourced: its types import
    requests: list[float] = []
    expected: list[float] = []

    def answer(request: Any, response: Any) -> Any:
        numbers = fields(request, FLOAT_TYPES + INTEGER_TYPES)
        value = getattr(request, numbers[0]) if numbers else 0
        requests.append(value)
        for flag in fields(response, ('boolean',)):
            setattr(response, flag, True)
        outputs = fields(response, FLOAT_TYPES + INTEGER_TYPES)
        expected.clear()
        for index, out in enumerate(outputs):
            kind = response.get_fields_and_field_types()[out]
            if subject == 'currency':
                result = round(value * RATES[index % len(RATES)], 2)
            else:
                result = math.factorial(int(value)) if 0 <= value <= 20 else 0
            result = int(result) if kind in INTEGER_TYPES else float(result)
            setattr(response, out, result)
            expected.append(result)
        return response

    s.node.create_service(srv, name, answer)
    s.wait(lambda: not process.running(), 15.0)
    s.add(
        Criterion(
            f'sends the command-line value ({found[1]} {argument} asks for {argument})',
            any(math.isclose(r, argument) for r in requests),
            'read the value from sys.argv[1] and put it into the request',
            f'requests {requests}',
        )
    )
    printed = judge.numbers_in(process.output)
    s.add(
        Criterion(
            f"prints the server's answer ({', '.join(f'{v:g}' for v in expected) or 'nothing asked'})",
            bool(expected) and all(any(math.isclose(v, p, abs_tol=0.006) for p in printed) for v in expected),
            "log the response's fields with self.get_logger().info(...)",
            judge.tail_lines(process.output, 1),
        )
    )
    client_ended(s, process)


@SECTION.check(
    'currency_client',
    '3.6 exercise',
    'olive_srvcli',
    'sends its command-line euros to the currency service and prints the three amounts',
    choice='3.6',
)
def check_currency_client(s: Session) -> None:
    """Check the currency client: it sends 100 euros, prints the three amounts and ends."""
    check_service_client(s, 'currency')


@SECTION.check(
    'factorial_server',
    '3.6 exercise',
    'olive_srvcli',
    'a service that answers the factorial of an integer (choose it or currency)',
    choice='3.6',
)
def check_factorial_server(s: Session) -> None:
    """Check the factorial server: it answers 5, 0 and 10 with their factorials."""
    check_service_server(s, 'factorial')


@SECTION.check(
    'factorial_client',
    '3.6 exercise',
    'olive_srvcli',
    'sends its command-line integer to the factorial service and prints the answer',
    choice='3.6',
)
def check_factorial_client(s: Session) -> None:
    """Check the factorial client: it sends 5, prints the answer and ends."""
    check_service_client(s, 'factorial')
