"""Checks of what the page (or any HTTP client) sends, each failing with one clear line (node-free)."""

import json
import math
from typing import Any

from ros2cli.names import did_you_mean, expand_topic_name

MAX_RATE = 1000.0  # Hz
MAX_TIMEOUT = 300.0  # s


class ApiError(Exception):
    """A request the API refuses: HTTP status and a one-line message for the page."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


def parse_json_object(body: bytes) -> dict[str, Any]:
    """The request body as a JSON object (an empty body is {})."""
    if not body.strip():
        return {}
    try:
        value = json.loads(body)
    except UnicodeDecodeError:
        raise ApiError(400, 'malformed JSON in the request body: not UTF-8 text') from None
    except json.JSONDecodeError as error:
        raise ApiError(400, f'malformed JSON in the request body: {error.msg} '
                            f'(line {error.lineno}, column {error.colno})') from None
    if not isinstance(value, dict):
        raise ApiError(400, f'the request body must be a JSON object, got {type(value).__name__}')
    return value


def check_keys(body: dict[str, Any], allowed: tuple[str, ...], required: tuple[str, ...] = ()) -> None:
    """Unknown keys (with the closest allowed one) and missing required keys are errors."""
    for key in body:
        if key not in allowed:
            raise ApiError(400, f"unknown key '{key}'{did_you_mean(key, allowed)}; "
                                f"expected: {', '.join(allowed)}")
    for key in required:
        if key not in body:
            raise ApiError(400, f"missing key '{key}'")


def positive_number(value: Any, what: str, maximum: float, unit: str) -> float:
    """A finite number in (0, maximum]; JSON numbers or numeric text (a query string)."""
    if isinstance(value, str):
        try:
            value = float(value)
        except ValueError:
            raise ApiError(400, f'{what} must be a number of {unit}, got {value!r}') from None
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ApiError(400, f'{what} must be a number of {unit}, got {json.dumps(value)}')
    if not math.isfinite(value) or not 0 < value <= maximum:
        raise ApiError(400, f'{what} must be greater than 0 and at most {maximum:g} {unit}, got {value:g}')
    return float(value)


def rate(value: Any) -> float:
    return positive_number(value, 'rate', MAX_RATE, 'Hz')


def timeout(value: Any) -> float:
    return positive_number(value, 'timeout', MAX_TIMEOUT, 's')


def boolean(value: Any, what: str) -> bool:
    if not isinstance(value, bool):
        raise ApiError(400, f'{what} must be true or false, got {json.dumps(value)}')
    return value


def name(value: Any, what: str) -> str:
    """A topic or service name as given (relative names resolve against '/')."""
    if not isinstance(value, str) or not value.strip():
        raise ApiError(400, f'{what} must be a non-empty string, got {json.dumps(value)}')
    return expand_topic_name(value.strip())


def optional_text(value: Any, what: str) -> str | None:
    if value is None or value == '':
        return None
    if not isinstance(value, str):
        raise ApiError(400, f'{what} must be a string, got {json.dumps(value)}')
    return value.strip()


def known_name(wanted: str, known: dict[str, list[str]], what: str) -> list[str]:
    """The types of a topic/service that exists; 404 naming the closest existing one otherwise."""
    if wanted not in known:
        hint = did_you_mean(wanted, known)
        raise ApiError(404, f"unknown {what} '{wanted}'{hint}")
    return known[wanted]


def single_type(wanted: str, types: list[str], what: str) -> str:
    """The one type of a topic/service; 400 when the graph shows several."""
    if len(types) != 1:
        raise ApiError(400, f"{what} '{wanted}' has several types ({', '.join(types)}); "
                            'give the one to use as "type"')
    return types[0]


def fields(value: Any, what: str) -> dict[str, Any]:
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise ApiError(400, f'{what} must be a JSON object of field values, got {json.dumps(value)}')
    return value


def identifier(text: str) -> int:
    if not text.isdigit():
        raise ApiError(404, f"no publisher '{text}'")
    return int(text)
