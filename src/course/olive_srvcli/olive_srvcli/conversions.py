"""The arithmetic behind the services, kept free of ROS so it can be tested directly."""

import math
from dataclasses import dataclass
from typing import Generic, TypeVar

ABSOLUTE_ZERO_C = -273.15
MAX_FACTORIAL_INPUT = 20  # 21! no longer fits the uint64 in Factorial.srv


def celsius_to_kelvin(temp_c: float) -> float:
    return temp_c + 273.15


def celsius_to_fahrenheit(temp_c: float) -> float:
    # The course listing writes 9 / 2, a typo: 100 °C is 212 °F.
    return temp_c * 9 / 5 + 32


Value = TypeVar('Value')


@dataclass(frozen=True)
class Outcome(Generic[Value]):
    """A computed value, or the reason there is none."""

    value: Value | None = None
    error: str = ''

    @property
    def ok(self) -> bool:
        return not self.error


def check_celsius(temp_c: float) -> str:
    """Why temp_c is not a physical temperature, or '' when it is."""
    if not math.isfinite(temp_c):
        return f'{temp_c} is not a finite temperature'
    if temp_c < ABSOLUTE_ZERO_C:
        return f'{temp_c} °C is below absolute zero ({ABSOLUTE_ZERO_C} °C)'
    return ''


def convert_euros(euros: float, rates: dict[str, float]) -> Outcome[dict[str, float]]:
    """Euros in each currency of rates (currency -> units per euro), rounded to cents."""
    if not math.isfinite(euros):
        return Outcome(error=f'{euros} is not a finite amount')
    if euros < 0:
        return Outcome(error=f'the amount must not be negative, got {euros} euros')
    return Outcome(value={name: round(euros * rate, 2) for name, rate in rates.items()})


def factorial(n: int) -> Outcome[int]:
    """N! for 0 <= n <= 20, exact."""
    if n < 0:
        return Outcome(error=f'the factorial of a negative number ({n}) is not defined')
    if n > MAX_FACTORIAL_INPUT:
        return Outcome(error=f'{n}! is too large for a 64-bit result; the largest input is '
                             f'{MAX_FACTORIAL_INPUT}')
    return Outcome(value=math.factorial(n))
