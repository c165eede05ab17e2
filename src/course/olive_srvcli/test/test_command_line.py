import pytest
from olive_srvcli.command_line import (
    UsageError,
    argument_or_exit,
    celsius_argument,
    euros_argument,
    integer_argument,
)


@pytest.mark.parametrize(('parse', 'argv', 'value'), [
    (celsius_argument, ['100'], 100.0),
    (celsius_argument, ['-273.15'], -273.15),
    (euros_argument, ['0'], 0.0),
    (integer_argument, ['20'], 20),
    (integer_argument, ['-3'], -3),  # the server refuses it, with its reason
])
def test_good_arguments(parse, argv, value):
    result = parse(argv)
    assert result == value
    assert type(result) is type(value)


@pytest.mark.parametrize(('parse', 'argv', 'reason'), [
    (celsius_argument, [], 'expected exactly one argument, a temperature in Celsius; got 0'),
    (celsius_argument, ['1', '2'], 'got 2'),
    (celsius_argument, ['warm'], "'warm' is not a number"),
    (celsius_argument, ['inf'], "'inf' is not a finite number"),
    (celsius_argument, ['-300'], 'below absolute zero'),
    (euros_argument, ['-0.5'], 'must not be negative'),
    (integer_argument, ['2.5'], "'2.5' is not an integer"),
    (integer_argument, [str(2**63)], 'does not fit'),
])
def test_bad_arguments_say_why(parse, argv, reason):
    with pytest.raises(UsageError, match=reason):
        parse(argv)


def test_argument_or_exit_skips_ros_arguments():
    argv = ['/x/lib/olive_srvcli/temp_client', '20', '--ros-args', '-r', '__node:=other']
    assert argument_or_exit(celsius_argument, '<celsius>', argv) == 20.0


def test_argument_or_exit_prints_one_line_and_exits_2(capsys):
    with pytest.raises(SystemExit) as exit_info:
        argument_or_exit(celsius_argument, '<celsius>', ['/x/lib/olive_srvcli/temp_client', 'warm'])
    assert exit_info.value.code == 2
    captured = capsys.readouterr()
    assert captured.out == ''
    assert captured.err == "temp_client: error: 'warm' is not a number (usage: temp_client <celsius>)\n"
