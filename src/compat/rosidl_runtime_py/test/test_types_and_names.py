"""Type lookup, installed interfaces and name rules, under upstream's names where upstream has them."""

import os

import pytest
from owl_common.graph import full_node_name, is_hidden_name, is_hidden_node, split_node_name
from owl_common.hints import did_you_mean
from rosidl_runtime_py import (
    get_interface_path,
    get_interfaces,
    get_message_interfaces,
    import_message_from_namespaced_type,
)
from rosidl_runtime_py.get_interfaces import (
    get_action_interfaces,
    get_interface_packages,
    get_service_interfaces,
)
from rosidl_runtime_py.utilities import (
    InvalidType,
    canonical_type,
    get_action,
    get_interface,
    get_message,
    get_namespaced_type,
    get_service,
    import_type,
    is_action,
    is_message,
    is_service,
    split_type,
)


def test_names():
    assert full_node_name('/', 'talker') == '/talker'
    assert full_node_name('/ns', 'talker') == '/ns/talker'
    assert split_node_name('ns/talker') == ('/ns', 'talker')
    assert split_node_name('/talker') == ('/', 'talker')
    assert is_hidden_node('/ns/_hidden')
    assert not is_hidden_node('/_ns/visible')
    assert is_hidden_name('/fibonacci/_action/status')
    assert not is_hidden_name('/chatter')
    assert did_you_mean('/chatt', ['/chatter', '/rosout']) == " (did you mean '/chatter'?)"
    assert did_you_mean('/xyz', ['/chatter']) == ''


def test_type_names():
    assert split_type('std_msgs/String', 'msg') == ('std_msgs', 'msg', 'String')
    assert canonical_type('std_srvs/SetBool', 'srv') == 'std_srvs/srv/SetBool'
    with pytest.raises(InvalidType, match="'std_msgs/srv/String' is not a message type name"):
        split_type('std_msgs/srv/String', 'msg')
    with pytest.raises(InvalidType, match="package 'std_msgs' has no message 'Strin' "
                                          r"\(did you mean 'String'\?\)"):
        import_type('std_msgs/msg/Strin', 'msg')
    with pytest.raises(InvalidType, match=r"it is 'std_srvs/srv/SetBool'"):
        import_type('std_srvs/msg/SetBool', 'msg')


def test_upstream_lookups_return_the_generated_classes():
    from std_msgs.msg import String
    from std_srvs.srv import SetBool
    from turtlesim.action import RotateAbsolute
    assert get_message('std_msgs/msg/String') is String
    assert get_message('std_msgs/String') is String
    assert get_service('std_srvs/srv/SetBool') is SetBool
    assert get_action('turtlesim/action/RotateAbsolute') is RotateAbsolute
    assert get_interface('std_srvs/srv/SetBool') is SetBool
    assert is_message(String)
    assert is_message(String())
    assert not is_message(SetBool)
    assert is_service(SetBool)
    assert not is_service(String)
    assert is_action(RotateAbsolute)
    assert not is_action(SetBool)
    namespaced = get_namespaced_type('std_msgs/msg/String')
    assert (namespaced.namespaces, namespaced.name) == (['std_msgs', 'msg'], 'String')
    assert import_message_from_namespaced_type(namespaced) is String


@pytest.mark.parametrize(('call', 'name', 'message'), [
    (get_message, 'std_msgs/msg/Strng', "did you mean 'String'"),
    (get_message, 'nonexistent_pkg/msg/X', "unknown package 'nonexistent_pkg'"),
    (get_service, 'std_msgs/msg/String', 'is not a service type name'),
    (get_interface, 'std_msgs/String', "expected '<package>/<msg|srv|action>/<Name>'"),
    (get_namespaced_type, 'String', "'String' is not a type name"),
])
def test_wrong_type_names_are_value_errors_of_one_line(call, name, message):
    with pytest.raises(ValueError, match=message) as caught:
        call(name)
    assert '\n' not in str(caught.value)


def test_installed_interfaces_as_upstream_lists_them():
    interfaces = get_interfaces(['std_srvs'])
    assert 'srv/SetBool' in interfaces['std_srvs']
    assert 'msg/String' in get_message_interfaces(['std_msgs'])['std_msgs']
    assert get_service_interfaces(['std_msgs'])['std_msgs'] == []
    assert 'action/RotateAbsolute' in get_action_interfaces(['turtlesim'])['turtlesim']
    assert 'std_msgs' in get_interface_packages()
    with pytest.raises(LookupError, match="Unknown package 'nope_msgs'"):
        get_interfaces(['nope_msgs'])


def test_interface_path_is_the_installed_definition():
    path = get_interface_path('std_msgs/msg/String')
    assert path.endswith(os.path.join('std_msgs', 'msg', 'String.msg'))
    assert os.path.isfile(path)
    assert get_interface_path('std_msgs/msg/String.idl').endswith('String.idl')
    with pytest.raises(LookupError, match="Could not find the interface 'std_msgs/msg/Nope'"):
        get_interface_path('std_msgs/msg/Nope')
    with pytest.raises(LookupError, match="Unknown package 'nope_msgs'"):
        get_interface_path('nope_msgs/msg/X')
    with pytest.raises(ValueError, match='is not'):
        get_interface_path('std_msgs/String')
