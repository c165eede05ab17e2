import math

import pytest
from olive_srvcli.conversions import (
    MAX_FACTORIAL_INPUT,
    celsius_to_fahrenheit,
    celsius_to_kelvin,
    check_celsius,
    convert_euros,
    factorial,
)


@pytest.mark.parametrize(('celsius', 'kelvin', 'fahrenheit'), [
    (0.0, 273.15, 32.0),
    (100.0, 373.15, 212.0),
    (-40.0, 233.15, -40.0),
    (-273.15, 0.0, -459.67),
])
def test_temperature_conversions(celsius, kelvin, fahrenheit):
    assert celsius_to_kelvin(celsius) == pytest.approx(kelvin)
    assert celsius_to_fahrenheit(celsius) == pytest.approx(fahrenheit)


def test_below_absolute_zero_is_not_a_temperature():
    assert check_celsius(-273.15) == ''
    assert 'absolute zero' in check_celsius(-273.16)
    assert check_celsius(math.nan)
    assert check_celsius(math.inf)


def test_euros_are_converted_with_each_rate_and_rounded_to_cents():
    outcome = convert_euros(10.0, {'usd': 1.16, 'gbp': 0.876})
    assert outcome.ok
    assert outcome.value == {'usd': 11.6, 'gbp': 8.76}


@pytest.mark.parametrize('euros', [-0.01, math.nan, math.inf])
def test_bad_amounts_are_refused_with_a_reason(euros):
    outcome = convert_euros(euros, {'usd': 1.0})
    assert not outcome.ok
    assert outcome.error


def test_factorial_is_exact_up_to_its_limit():
    assert factorial(0).value == 1
    assert factorial(1).value == 1
    assert factorial(5).value == 120
    assert factorial(MAX_FACTORIAL_INPUT).value == 2432902008176640000
    assert factorial(MAX_FACTORIAL_INPUT).value < 2**64


@pytest.mark.parametrize('n', [-1, MAX_FACTORIAL_INPUT + 1, 10**6])
def test_factorial_refuses_what_it_cannot_answer(n):
    outcome = factorial(n)
    assert not outcome.ok
    assert str(n) in outcome.error
