"""olive_srvcli over real DDS: every service round trip and every bad input of the clients."""

import math

import pytest
from olive_interfaces.srv import CurrencyConv, Factorial, TempConv

TEMPERATURE_LINE = (
    '[temp_client]: The Temperature of {c} Celsius is equal to {k} Kelvin and {f} Fahrenheit')


@pytest.mark.parametrize(('celsius', 'kelvin', 'fahrenheit'), [
    ('0.0', '273.15', '32.0'),
    ('100', '373.15', '212.0'),
])
def test_temp_client_prints_the_course_line(ros, celsius, kelvin, fahrenheit):
    server = ros.run('olive_srvcli', 'temp_server')
    client = ros.run('olive_srvcli', 'temp_client', celsius)
    assert client.wait(15) == 0, client.output
    expected = TEMPERATURE_LINE.format(c=float(celsius), k=kelvin, f=fahrenheit)
    assert expected in client.output
    server.wait_for(rf'Temperature in Celsius: {float(celsius)}')


def test_temp_client_waits_for_the_server_and_says_so(ros):
    client = ros.run('olive_srvcli', 'temp_client', '20')
    client.wait_for(r'\[temp_client\]: service not available, waiting again\.\.$', timeout=10, count=2)
    ros.run('olive_srvcli', 'temp_server')
    assert client.wait(15) == 0
    assert 'is equal to 293.15 Kelvin and 68.0 Fahrenheit' in client.output


def test_temp_client_ctrl_c_while_waiting_exits_cleanly(ros):
    client = ros.run('olive_srvcli', 'temp_client', '20')
    client.wait_for('service not available')
    client.stop_cleanly()
    assert 'Traceback' not in client.output


def test_temp_server_answers_nan_below_absolute_zero(ros):
    server = ros.run('olive_srvcli', 'temp_server')
    response = ros.probe.call(TempConv, 'temp_conversion', TempConv.Request(temp_c=-300.0))
    assert math.isnan(response.temp_k)
    assert math.isnan(response.temp_f)
    server.wait_for('below absolute zero')
    response = ros.probe.call(TempConv, 'temp_conversion', TempConv.Request(temp_c=-273.15))
    assert response.temp_k == pytest.approx(0.0)


@pytest.mark.parametrize(('executable', 'args', 'message'), [
    ('temp_client', [], 'expected exactly one argument'),
    ('temp_client', ['1', '2'], 'expected exactly one argument'),
    ('temp_client', ['warm'], "'warm' is not a number"),
    ('temp_client', ['nan'], "'nan' is not a finite number"),
    ('temp_client', ['-273.2'], 'below absolute zero'),
    ('currency_client', ['-5'], 'must not be negative'),
    ('currency_client', ['ten'], "'ten' is not a number"),
    ('factorial_client', ['2.5'], "'2.5' is not an integer"),
    ('factorial_client', [], 'expected exactly one argument'),
    ('factorial_client', [str(2**70)], 'does not fit'),
])
def test_client_input_errors_print_one_line_and_exit_2(ros, executable, args, message):
    client = ros.run('olive_srvcli', executable, *args)
    assert client.wait(10) == 2
    assert client.lines == [client.lines[0]], client.output
    assert message in client.lines[0]
    assert f'usage: {executable}' in client.lines[0]


def test_currency_round_trip_uses_the_rate_parameters(ros):
    ros.run('olive_srvcli', 'currency_server')
    client = ros.run('olive_srvcli', 'currency_client', '10')
    assert client.wait(15) == 0, client.output
    assert '10.0 Euros are 11.6 US dollars, 8.8 British pounds and 9.3 Swiss francs' in client.output
    [result] = ros.probe.set_parameters('/currency_service', usd_per_eur=2.0)
    assert result.successful
    response = ros.probe.call(CurrencyConv, 'currency_conversion', CurrencyConv.Request(euros=3.0))
    assert response.success
    assert response.dollars == 6.0


def test_currency_server_refuses_negative_amount_and_bad_rates(ros):
    ros.run('olive_srvcli', 'currency_server')
    response = ros.probe.call(CurrencyConv, 'currency_conversion', CurrencyConv.Request(euros=-1.0))
    assert not response.success
    assert 'negative' in response.message
    for bad in (-1.0, 0.0, 'cheap'):
        [result] = ros.probe.set_parameters('/currency_service', gbp_per_eur=bad)
        assert not result.successful
    assert ros.probe.get_parameters('/currency_service', 'gbp_per_eur') == [0.88]


def test_factorial_round_trip_and_refusals(ros):
    ros.run('olive_srvcli', 'factorial_server')
    client = ros.run('olive_srvcli', 'factorial_client', '20')
    assert client.wait(15) == 0, client.output
    assert 'The factorial of 20 is 2432902008176640000' in client.output
    for n, reason in ((-3, 'negative'), (21, 'too large')):
        response = ros.probe.call(Factorial, 'factorial', Factorial.Request(n=n))
        assert not response.success
        assert reason in response.message
    refused = ros.run('olive_srvcli', 'factorial_client', '25')
    assert refused.wait(15) == 1
    assert 'The server refused: 25! is too large' in refused.output
    assert 'Traceback' not in refused.output


@pytest.mark.parametrize('server', ['temp_server', 'currency_server', 'factorial_server'])
def test_servers_stop_cleanly_on_ctrl_c(ros, server):
    process = ros.run('olive_srvcli', server)
    ros.probe.wait_until_spinning(server.replace('_server', '_service'))
    process.stop_cleanly()
    assert 'Traceback' not in process.output
