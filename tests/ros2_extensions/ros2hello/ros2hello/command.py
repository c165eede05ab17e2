"""`ros2 hello`: a command as a third party writes one for upstream ros2cli."""

from ros2cli.command import CommandExtension, add_subparsers_on_demand


class HelloCommand(CommandExtension):
    """Greet the world from a third party's package."""

    def add_arguments(self, parser, cli_name):
        self._subparser = parser
        add_subparsers_on_demand(parser, cli_name, '_verb', 'ros2hello.verb', required=False)

    def main(self, *, parser, args):
        if not hasattr(args, '_verb'):
            self._subparser.print_help()
            return 0
        return args._verb.main(args=args)
