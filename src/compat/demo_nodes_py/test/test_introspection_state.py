"""The introspection parameters' values, without a node."""

from demo_nodes_py.services.add_two_ints_server import wrap_int64
from demo_nodes_py.services.introspection import introspection_state
from rclpy.service_introspection import ServiceIntrospectionState


def test_each_value_names_its_state():
    assert introspection_state('disabled') == ServiceIntrospectionState.OFF
    assert introspection_state('metadata') == ServiceIntrospectionState.METADATA
    assert introspection_state('contents') == ServiceIntrospectionState.CONTENTS


def test_other_values_are_refused_with_the_reason():
    assert introspection_state('Contents') == "must be one of 'disabled', 'metadata', or 'contents'"
    assert introspection_state('') == "must be one of 'disabled', 'metadata', or 'contents'"
    assert introspection_state(2) == 'must be a string'
    assert introspection_state(True) == 'must be a string'


def test_a_sum_wraps_as_an_int64_does():
    assert wrap_int64(2 + 3) == 5
    assert wrap_int64(2**63 - 1 + 1) == -2**63
    assert wrap_int64(-2**63 - 1) == 2**63 - 1
