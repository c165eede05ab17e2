"""Every `ros2 <command>`: its name and the module that implements it, imported only when used.

A command module provides:
    DESCRIPTION: str                                   one line for `ros2 -h`
    add_arguments(parser: argparse.ArgumentParser, cli_name: str) -> None
                                                       its options and verb sub-parsers
    main(args: argparse.Namespace) -> int | str | None the command's work (see cli.py for what the
                                                       return value means)
Commands that live in other packages (pkg, launch) are listed here too; when such a package is not
installed, `ros2 <command>` says so in one line.
"""

COMMANDS: dict[str, tuple[str, str]] = {
    # name: (module, package that provides it)
    'action': ('ros2cli.command.action', 'ros2cli'),
    'daemon': ('ros2cli.command.daemon', 'ros2cli'),
    'interface': ('ros2cli.command.interface', 'ros2cli'),
    'node': ('ros2cli.command.node', 'ros2cli'),
    'param': ('ros2cli.command.param', 'ros2cli'),
    'run': ('ros2cli.command.run', 'ros2cli'),
    'service': ('ros2cli.command.service', 'ros2cli'),
    'topic': ('ros2cli.command.topic', 'ros2cli'),
    'pkg': ('ros2pkg.command', 'ros2pkg'),
    'launch': ('ros2launch.command', 'ros2launch'),
}
