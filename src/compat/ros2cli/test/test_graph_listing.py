"""The list/type/find output shared by `ros2 topic`, `service` and `action`, without a graph."""

from ros2cli.graph_listing import print_listing, print_names_of_type, print_types, types_of

ENTRIES = [['/add', ['example_interfaces/srv/AddTwoInts']],
           ['/chatter', ['std_msgs/msg/String', 'other_msgs/msg/String']],
           ['/echo', ['std_msgs/msg/String']]]


class FakeStrategy:
    """A graph that shows its entries only after the first wait, like late discovery."""

    def __init__(self) -> None:
        self.graph: list = []
        self.waited = False

    def wait_until(self, condition) -> bool:
        self.waited = True
        self.graph = ENTRIES
        return condition()


def test_types_of_a_known_and_an_unknown_name():
    assert types_of(ENTRIES, '/chatter') == ['std_msgs/msg/String', 'other_msgs/msg/String']
    assert types_of(ENTRIES, '/chat') is None


def test_listing_with_types_and_count(capsys):
    assert print_listing(ENTRIES, show_types=False, count_only=False) == 0
    assert capsys.readouterr().out == '/add\n/chatter\n/echo\n'
    print_listing(ENTRIES, show_types=True, count_only=False)
    assert capsys.readouterr().out.splitlines()[1] == '/chatter [std_msgs/msg/String, other_msgs/msg/String]'
    print_listing(ENTRIES, show_types=True, count_only=True)
    assert capsys.readouterr().out == '3\n'


def test_names_of_a_type_and_their_count(capsys):
    assert print_names_of_type(ENTRIES, 'std_msgs/msg/String', count_only=False) == 0
    assert capsys.readouterr().out == '/chatter\n/echo\n'
    print_names_of_type(ENTRIES, 'nope_msgs/msg/Nope', count_only=True)
    assert capsys.readouterr().out == '0\n'


def test_types_waits_for_discovery_and_an_unknown_name_exits_1_silently(capsys):
    strategy = FakeStrategy()
    assert print_types(strategy, lambda graph: graph, '/chatter') == 0
    assert strategy.waited
    assert capsys.readouterr().out == 'std_msgs/msg/String\nother_msgs/msg/String\n'
    assert print_types(FakeStrategy(), lambda graph: graph, '/missing') == 1
    assert capsys.readouterr().out == ''
