"""`ros2 pkg xml`: a package's manifest, or the text of some of its elements."""

from __future__ import annotations

import argparse
import os

from ros2cli.verb import VerbExtension

from ros2pkg.api import PACKAGE_NOT_FOUND, _package_argument, get_share_directory


class XmlVerb(VerbExtension):
    """Output the XML of the package manifest or a specific tag."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the package name and -t/--tag."""
        _package_argument(parser)
        parser.add_argument('-t', '--tag', help="The package's xml's tag to print")

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the manifest or a tag's text: see main_xml."""
        return main_xml(args)


def main_xml(args: argparse.Namespace) -> int | str:
    """Print a package's package.xml, or the text of each element that --tag finds in it.

    Returns an error message when the package, its manifest or the tag is not found, or it cannot be read.
    """
    import xml.etree.ElementTree as ET  # lazy: slow to import, and `ros2 pkg -h` imports this module

    share = get_share_directory(args.package_name)
    if share is None:
        return PACKAGE_NOT_FOUND
    manifest = os.path.join(share, 'package.xml')
    if not os.path.isfile(manifest):
        return 'Package xml manifest not found'
    try:
        tree = ET.parse(manifest)
    except (ET.ParseError, OSError) as error:
        return f'Package xml manifest {manifest} cannot be read: {error}'
    if args.tag is None:
        ET.dump(tree)
        return 0
    try:
        elements = tree.getroot().findall(args.tag)
    except (SyntaxError, KeyError, TypeError):  # not an ElementPath expression, e.g. '['
        elements = []
    if not elements:
        return 'XML tag not found'
    for element in elements:
        print(element.text)
    return 0
