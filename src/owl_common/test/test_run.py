import signal

import pytest
from owl_common.run import StopRequest


def test_a_stop_before_the_main_loop_interrupts_what_the_main_thread_is_doing():
    stop = StopRequest()
    with pytest.raises(KeyboardInterrupt):
        stop(signal.SIGINT, None)
    assert stop.requested


def test_a_stop_during_the_main_loop_is_only_recorded_for_it():
    stop = StopRequest()
    stop.polling = True
    stop(signal.SIGTERM, None)
    assert stop.requested
