"""A test whose prerequisite is missing (a browser, Xvfb, network namespaces): skip here, fail in CI.

On a developer's machine a missing Chromium or Xvfb is one skip line with the install command. In
CI (`CI=true`) nothing may pass untested: the same test fails, so a green run means it ran.
"""

import os
from typing import NoReturn

import pytest


def in_ci() -> bool:
    return os.environ.get('CI') == 'true'


def prerequisite_missing(reason: str) -> NoReturn:
    """Skip the test for reason, or fail it in CI."""
    if in_ci():
        pytest.fail(f'{reason}; in CI (CI=true) a test that cannot run fails', pytrace=False)
    pytest.skip(reason)
