"""Whether a Fast DDS profile keeps our graph messages away from Humble (no DDS library imported).

config/fastdds.xml gives the ros_discovery_info readers and writers of every process of ours a
partition of its own; a Humble participant (default partition) then never reads a graph message
in Jazzy's layout. A profile file of the user's own (FASTRTPS_DEFAULT_PROFILES_FILE) may lack it.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ElementTree
from pathlib import Path

JAZZY_GRAPH_PARTITION = 'owl_kit_lab_jazzy_graph'
DISCOVERY_TOPIC = 'ros_discovery_info'
NAMESPACE = '{http://www.eprosima.com}'


def profile_protects(path: Path) -> bool:
    """True when the profile file puts both ros_discovery_info endpoints in our graph partition."""
    try:
        root = ElementTree.parse(path).getroot()
    except (OSError, ElementTree.ParseError):
        return False
    found = set()
    for element in root.iter():
        kind = element.tag.removeprefix(NAMESPACE)
        if kind in ('data_writer', 'data_reader') and element.get('profile_name') == DISCOVERY_TOPIC:
            names = [name.text for name in element.iter(NAMESPACE + 'name')] + [
                name.text for name in element.iter('name')]
            if JAZZY_GRAPH_PARTITION in names:
                found.add(kind)
    return found == {'data_writer', 'data_reader'}


def profile_in_effect(environ: dict[str, str] | None = None) -> Path | None:
    """The Fast DDS profile file a process started here reads (Fast DDS 2.14's rules)."""
    env = os.environ if environ is None else environ
    if env.get('FASTRTPS_DEFAULT_PROFILES_FILE'):
        return Path(env['FASTRTPS_DEFAULT_PROFILES_FILE'])
    local = Path('DEFAULT_FASTRTPS_PROFILES.xml')
    return local if local.exists() else None
