"""The `$(...)` syntax and the strictness of the XML/YAML frontends, without running anything."""

import pytest
from launch import LaunchContext
from launch.frontend import LaunchFileError, load_launch_file, parse_substitution
from launch.utilities import perform_substitutions


def render(text: str, **configurations: str) -> str:
    context = LaunchContext()
    context.launch_configurations.update(configurations)
    return perform_substitutions(context, parse_substitution(text))


def test_literal_text_and_nested_substitutions():
    assert render('plain ) text') == 'plain ) text'
    assert render('a $(var x) b', x='1') == 'a 1 b'
    assert render('$(var $(var which))', which='x', x='deep') == 'deep'
    assert render('$(var missing fallback)') == 'fallback'


def test_quoted_arguments_keep_spaces_and_may_hold_substitutions():
    assert render("$(eval '$(var a) + 1')", a='41') == '42'
    assert render('$(var missing "two words")') == 'two words'
    assert render(r'escaped \$(var x)', x='no') == 'escaped $(var x)'


@pytest.mark.parametrize(('text', 'message'), [
    ('$(nosuch a)', 'Unknown substitution: nosuch'),
    ('$(var a', 'unterminated substitution'),
    ('$(var)', "substitution 'var' expects 1 to 2 argument"),
    ('$( var x)', "expected a name after '\\$\\('"),
])
def test_malformed_substitutions_are_errors(text, message):
    with pytest.raises(ValueError, match=message):
        parse_substitution(text)


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_xml_unknown_attribute_names_file_line_and_attribute(tmp_path):
    path = write(tmp_path, 'x.launch.xml',
                 '<launch>\n  <log message="hi"/>\n  <log message="a" colour="red"/>\n</launch>\n')
    with pytest.raises(LaunchFileError) as error:
        load_launch_file(path, 'xml')
    assert str(error.value) == f"{path}:3: Unexpected attribute(s) found in `log`: {{'colour'}}"


def test_xml_unknown_nested_tag_and_unknown_tag(tmp_path):
    nested = write(tmp_path, 'n.launch.xml',
                   '<launch>\n<executable cmd="true"><foo/></executable>\n</launch>')
    expected = r'n.launch.xml:2: Unexpected nested tag\(s\) found in `executable`'
    with pytest.raises(LaunchFileError, match=expected):
        load_launch_file(nested, 'xml')
    unknown = write(tmp_path, 'u.launch.xml', '<launch>\n\n<nodes/>\n</launch>')
    with pytest.raises(LaunchFileError, match=r'u.launch.xml:3: Unrecognized entity of the type: nodes'):
        load_launch_file(unknown, 'xml')


def test_yaml_unknown_key_names_file_line_and_key(tmp_path):
    path = write(tmp_path, 'y.launch.yaml',
                 'launch:\n- log:\n    message: hi\n- log:\n    message: a\n    colour: red\n')
    with pytest.raises(LaunchFileError) as error:
        load_launch_file(path, 'yaml')
    assert str(error.value) == f"{path}:4: Unexpected key(s) found in `log`: {{'colour'}}"


@pytest.mark.parametrize(('name', 'text', 'fmt', 'message'), [
    ('r.xml', '<group/>', 'xml', "Expected 'launch' as root tag"),
    ('b.xml', '<launch><log message="x"></launch>', 'xml', 'invalid XML: mismatched tag'),
    ('r.yaml', 'group: []\n', 'yaml', "Expected 'launch' as root tag"),
    ('t.yaml', 'launch: []\nother: 1\n', 'yaml', 'Expected only one root'),
    ('m.yaml', 'launch: [\n', 'yaml', 'invalid YAML'),
    ('c.xml', '<launch><log message="x" if="1" unless="0"/></launch>', 'xml', "'if' and 'unless'"),
    ('s.xml', '<launch><group scoped="maybe"/></launch>', 'xml', 'must be true or false'),
])
def test_malformed_files(tmp_path, name, text, fmt, message):
    with pytest.raises(LaunchFileError, match=message):
        load_launch_file(write(tmp_path, name, text), fmt)


def test_command_lines_split_like_a_shell_around_substitutions():
    from launch.actions.execute_process import split_command_line

    context = LaunchContext()
    context.launch_configurations.update({'msg': 'two words', 'topic': 'chat'})
    line = "ros2 topic pub /$(var topic)_x std_msgs/String '{data: $(var msg)}' \"\" $(var msg)"
    argv = [perform_substitutions(context, item) for item in split_command_line(parse_substitution(line))]
    assert argv == ['ros2', 'topic', 'pub', '/chat_x', 'std_msgs/String', '{data: two words}', '',
                    'two words']
    with pytest.raises(ValueError, match='cannot split command line'):
        split_command_line(parse_substitution("echo 'unclosed"))


def test_action_construction_errors_name_the_tag_location(tmp_path):
    path = write(tmp_path, 'c.launch.xml',
                 '<launch>\n  <arg name="c" default="z">\n    <choice value="a"/>\n  </arg>\n</launch>\n')
    expected = r"c.launch.xml:2: RuntimeError: Provided default_value 'z' is not in"
    with pytest.raises(LaunchFileError, match=expected):
        load_launch_file(path, 'xml')
