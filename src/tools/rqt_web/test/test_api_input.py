"""Checks of the API's input: each failure is one line with a status code."""

import pytest
from owl_web.codec import ApiError
from rqt_web import api_input


def refused(call, *args) -> ApiError:
    with pytest.raises(ApiError) as caught:
        call(*args)
    assert '\n' not in caught.value.message
    return caught.value


@pytest.mark.parametrize(('value', 'message'), [
    (0, 'rate must be greater than 0 and at most 1000 Hz, got 0'),
    (-1.5, 'rate must be greater than 0 and at most 1000 Hz, got -1.5'),
    (5000, 'rate must be greater than 0 and at most 1000 Hz, got 5000'),
    ('fast', "rate must be a number of Hz, got 'fast'"),
    (True, 'rate must be a number of Hz, got true'),
    (None, 'rate must be a number of Hz, got null'),
    (float('nan'), 'rate must be greater than 0 and at most 1000 Hz, got nan'),
])
def test_bad_rates(value, message):
    error = refused(api_input.rate, value)
    assert (error.status, error.message) == (400, message)


def test_good_numbers():
    assert api_input.rate(10) == 10.0
    assert api_input.rate('2.5') == 2.5
    assert api_input.timeout(0.5) == 0.5
    assert refused(api_input.timeout, 301).message == \
        'timeout must be greater than 0 and at most 300 s, got 301'


def test_names_and_types():
    assert api_input.name('turtle1/cmd_vel', 'topic') == '/turtle1/cmd_vel'
    assert refused(api_input.name, '', 'topic').message == 'topic must be a non-empty string, got ""'
    assert refused(api_input.name, 3, 'service').message == 'service must be a non-empty string, got 3'
    known = {'/spawn': ['turtlesim/srv/Spawn'], '/kill': ['turtlesim/srv/Kill']}
    assert api_input.known_name('/spawn', known, 'service') == ['turtlesim/srv/Spawn']
    error = refused(api_input.known_name, '/spwan', known, 'service')
    assert (error.status, error.message) == (404, "unknown service '/spwan' (did you mean '/spawn'?)")
    assert api_input.single_type('/a', ['x/msg/A'], 'topic') == 'x/msg/A'
    assert refused(api_input.single_type, '/a', ['x/msg/A', 'x/msg/B'], 'topic').message == \
        "topic '/a' has several types (x/msg/A, x/msg/B); give the one to use as \"type\""


def test_fields_texts_and_ids():
    assert api_input.fields(None, 'fields') == {}
    assert refused(api_input.fields, [1], 'fields').message == \
        'fields must be a JSON object of field values, got [1]'
    assert api_input.identifier('12') == 12
    assert refused(api_input.identifier, 'abc').status == 404
    assert api_input.optional_text('', 'type') is None
    assert refused(api_input.optional_text, 5, 'type').message == 'type must be a string, got 5'
    assert api_input.query_text({'type': 'std_msgs/msg/String'}, 'type') == 'std_msgs/msg/String'
    assert refused(api_input.query_text, {'type': ''}, 'type').message == "missing query parameter 'type'"
