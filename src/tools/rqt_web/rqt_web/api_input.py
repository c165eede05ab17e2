"""Checks of what the page (or any HTTP or WebSocket client) sends, each failing with one clear line.

Node-free. The generic ones (JSON objects, keys, booleans) are owl_web.codec's.
"""

import json
import math
from typing import Any

from owl_common.graph import expand_topic_name
from owl_common.hints import did_you_mean
from owl_web.codec import ApiError

MAX_RATE = 1000.0  # Hz
MAX_TIMEOUT = 300.0  # s


def positive_number(value: object, what: str, maximum: float, unit: str) -> float:
    """A finite number in (0, maximum]; JSON numbers or numeric text (a query string).

    The checks here take `object`: parsed JSON may be anything, and they find out what it is.
    """
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


def rate(value: object) -> float:
    """A publishing rate in Hz, more than 0 and at most MAX_RATE; ApiError 400 otherwise."""
    return positive_number(value, 'rate', MAX_RATE, 'Hz')


def timeout(value: object) -> float:
    """A service call's timeout in s, more than 0 and at most MAX_TIMEOUT; ApiError 400 otherwise."""
    return positive_number(value, 'timeout', MAX_TIMEOUT, 's')


def name(value: object, what: str) -> str:
    """A topic or service name as given (relative names resolve against '/')."""
    if not isinstance(value, str) or not value.strip():
        raise ApiError(400, f'{what} must be a non-empty string, got {json.dumps(value)}')
    return expand_topic_name(value.strip())


def optional_text(value: object, what: str) -> str | None:
    """A string without its outer spaces, or None when it is missing or empty; 400 for a non-string."""
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


def fields(value: object, what: str) -> dict[str, Any]:
    """A JSON object of field values ({} when missing); 400 for anything else."""
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise ApiError(400, f'{what} must be a JSON object of field values, got {json.dumps(value)}')
    return value


def identifier(text: str) -> int:
    """A Message Publisher row's id from the URL path; 404 when it is not a number."""
    if not text.isdigit():
        raise ApiError(404, f"no publisher '{text}'")
    return int(text)


def query_text(query: dict[str, str], key: str) -> str:
    """A required query parameter (?type=...)."""
    if not query.get(key):
        raise ApiError(400, f"missing query parameter '{key}'")
    return query[key]
