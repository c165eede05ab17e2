"""The field forms of Message Publisher and Service Caller."""

from geometry_msgs.msg import Twist
from rqt_web.interface_template import field_template
from sensor_msgs.msg import CameraInfo


def test_nested_messages_get_nested_fields():
    template = field_template(Twist())
    assert [entry['name'] for entry in template] == ['linear', 'angular']
    assert template[0]['type'] == 'geometry_msgs/Vector3'
    assert template[0]['fields'] == [{'name': axis, 'type': 'double', 'default': 0.0} for axis in 'xyz']


def test_sequences_and_arrays_are_one_cell_with_their_default():
    template = {entry['name']: entry for entry in field_template(CameraInfo())}
    assert template['d'] == {'name': 'd', 'type': 'sequence<double>', 'default': [], 'sequence': True}
    assert template['k']['default'] == [0.0] * 9
    assert template['k']['sequence'] is True
    assert template['distortion_model'] == {'name': 'distortion_model', 'type': 'string', 'default': ''}

