"""XML and YAML launch_ros tags: what each turns into on the command line.

The tags are <node>, <param>, <remap>, <push_ros_namespace>, <set_parameter>, <set_remap> and
<set_parameters_from_file>.
"""

import textwrap

import pytest
import yaml
from launch import LaunchContext
from launch.frontend import load_launch_file
from launch_ros.actions import Node

XML = '''
<launch>
  <arg name="ns" default="outer"/>
  <group>
    <push-ros-namespace namespace="$(var ns)"/>
    <set_parameter name="use_sim_time" value="true"/>
    <set_parameters_from_file filename="GLOBAL"/>
    <set_remap from="chatter" to="talk"/>
    <node pkg="random_number_ps" exec="random_number_publisher" name="pub" namespace="inner"
          exec_name="numbers" args="--flag 'two words'" ros_args="--log-level debug">
      <param name="lower_limit" value="5"/>
      <param name="names" value="a,b" value-sep="," type="list_of_str"/>
      <param name="as_text" value="42" type="str"/>
      <param name="group">
        <param name="ratio" value="0.5"/>
      </param>
      <remap from="random_numbers" to="numbers"/>
      <env name="OWL_VAR" value="1"/>
    </node>
  </group>
  <node pkg="random_number_ps" exec="random_number_publisher"/>
</launch>
'''
YAML = '''
launch:
- arg: {name: ns, default: outer}
- group:
    children:
    - push_ros_namespace: {namespace: $(var ns)}
    - set_parameter: {name: use_sim_time, value: true}
    - set_parameters_from_file: {filename: GLOBAL}
    - set_remap: {from: chatter, to: talk}
    - node:
        pkg: random_number_ps
        exec: random_number_publisher
        name: pub
        namespace: inner
        exec_name: numbers
        args: "--flag 'two words'"
        ros_args: --log-level debug
        param:
        - {name: lower_limit, value: 5}
        - {name: names, value: [a, b]}
        - {name: as_text, value: '42', type: str}
        - name: group
          param:
          - {name: ratio, value: 0.5}
        remap:
        - {from: random_numbers, to: numbers}
        env:
        - {name: OWL_VAR, value: '1'}
- node: {pkg: random_number_ps, exec: random_number_publisher}
'''


def prepared_nodes(entities, context):
    """Visit like the launch service, but only prepare Nodes (no process is started)."""
    nodes = []
    for entity in entities:
        if isinstance(entity, Node):
            entity._expand_names(context)
            entity._prepare(context)
            nodes.append(entity)
        else:
            nodes += prepared_nodes(entity.visit(context) or [], context)
    return nodes


@pytest.mark.parametrize(('name', 'text'), [('tags.launch.xml', XML), ('tags.launch.yaml', YAML)])
def test_ros_tags_build_the_same_command_line(tmp_path, name, text):
    global_file = tmp_path / 'global.yaml'
    global_file.write_text('/**:\n  ros__parameters:\n    upper_limit: 9\n')
    path = tmp_path / name
    path.write_text(textwrap.dedent(text).replace('GLOBAL', str(global_file)))
    context = LaunchContext()
    grouped, plain = prepared_nodes([load_launch_file(str(path), name.split('.')[-1])], context)
    argv = grouped.process_description.final_cmd
    assert grouped.process_description.final_name.startswith('numbers-')
    assert argv[1:10] == ['--flag', 'two words', '--ros-args', '--log-level', 'debug', '--ros-args',
                          '-r', '__node:=pub', '-r']
    assert argv[10:16] == ['__ns:=/outer/inner', '-p', 'use_sim_time:=True', '--params-file',
                           str(global_file), '--params-file']
    with open(argv[16]) as handle:
        assert yaml.safe_load(handle) == {'/outer/inner/pub': {'ros__parameters': {
            'lower_limit': 5, 'names': ['a', 'b'], 'as_text': '42', 'group.ratio': 0.5}}}
    assert argv[17:] == ['-r', 'chatter:=talk', '-r', 'random_numbers:=numbers']
    assert grouped.process_description.final_env['OWL_VAR'] == '1'
    # Outside the group: no pushed namespace, parameters or remaps.
    assert plain.process_description.final_cmd[1:] == ['--ros-args']
