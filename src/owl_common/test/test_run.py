import signal

import pytest
from owl_common.run import StopRequest


def test_a_stop_before_spinning_interrupts_what_the_main_thread_is_doing():
    stop = StopRequest()
    with pytest.raises(KeyboardInterrupt):
        stop(signal.SIGINT, None)
    assert stop.requested


def test_a_stop_while_spinning_is_only_recorded_for_the_spin_loop():
    stop = StopRequest()
    stop.spinning = True
    stop(signal.SIGTERM, None)
    assert stop.requested
