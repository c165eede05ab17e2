"""`ros2 hello world [--name NAME] [--times N]`."""

from ros2cli.verb import VerbExtension


class WorldVerb(VerbExtension):
    """Print a greeting."""

    def add_arguments(self, parser, cli_name):
        parser.add_argument('--name', default='world', help='Who to greet')
        parser.add_argument('--times', type=int, default=1, help='How many times')

    def main(self, *, args):
        if args.times < 1:
            return f'--times must be at least 1, got {args.times}'
        for _ in range(args.times):
            print(f'hello, {args.name} (from the package ros2hello)')
        return 0
