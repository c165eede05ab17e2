"""Node Graph: the ROS graph as boxes and arrows, laid out in layers (node-free, plain data).

Like rqt_graph's "Nodes/Topics (all)" view: a box per node and per topic, an arrow from a
publishing node to its topic and from a topic to each subscribing node.
"""

from collections.abc import Callable
from dataclasses import dataclass, field

from ros2cli.names import is_hidden_name, is_hidden_node

# rqt_graph hides these by default ("Debug" and "Params" in its Hide box).
DEBUG_TOPICS = frozenset({'/rosout', '/rosout_agg', '/parameter_events', '/statistics'})

# Geometry of the layout in pixels; the page draws with a 12 px monospace font.
CHAR_WIDTH = 7.3
BOX_PADDING = 24
BOX_HEIGHT = 30
ROW_GAP = 18
COLUMN_GAP = 70
ORDERING_SWEEPS = 4


@dataclass
class GraphModel:
    """Visible nodes and topics (full names) and the arrows between them."""

    nodes: list[str] = field(default_factory=list)
    topics: dict[str, list[str]] = field(default_factory=dict)  # topic -> types
    edges: list[tuple[str, str]] = field(default_factory=list)  # (from, to), names of boxes


def build_model(endpoints: dict[str, tuple[list[tuple[str, list[str]]], list[tuple[str, list[str]]]]],
                hide_debug: bool = True, hide_leaf_topics: bool = False) -> GraphModel:
    """The graph to draw from {node: (published [(topic, types)], subscribed [(topic, types)])}.

    hide_debug (rqt_graph's "Debug", on by default there too) hides /rosout, /parameter_events
    and hidden nodes and topics (a name part starting with '_', e.g. `ros2 topic pub`'s
    /_ros2cli_1234 node); hide_leaf_topics hides topics with only publishers or only subscribers.
    """
    def shown(name: str, is_hidden: Callable[[str], bool]) -> bool:
        return not hide_debug or not (is_hidden(name) or name in DEBUG_TOPICS)

    publishers: dict[str, set[str]] = {}
    subscribers: dict[str, set[str]] = {}
    types: dict[str, set[str]] = {}
    nodes = sorted(node for node in endpoints if shown(node, is_hidden_node))
    for node in nodes:
        published, subscribed = endpoints[node]
        for side, entries in ((publishers, published), (subscribers, subscribed)):
            for topic, topic_types in entries:
                if not shown(topic, is_hidden_name):
                    continue
                side.setdefault(topic, set()).add(node)
                types.setdefault(topic, set()).update(topic_types)
    topics = sorted(types)
    if hide_leaf_topics:
        topics = [t for t in topics if publishers.get(t) and subscribers.get(t)]
    model = GraphModel(nodes=nodes, topics={t: sorted(types[t]) for t in topics})
    for topic in topics:
        model.edges += [(node, topic) for node in sorted(publishers.get(topic, ()))]
        model.edges += [(topic, node) for node in sorted(subscribers.get(topic, ()))]
    return model


def _layers(boxes: list[str], edges: list[tuple[str, str]]) -> dict[str, int]:
    """Longest-path layering after turning back edges of a depth-first search around."""
    successors: dict[str, list[str]] = {box: [] for box in boxes}
    for source, target in edges:
        successors[source].append(target)
    state: dict[str, int] = {}  # 1: on the DFS stack, 2: done
    forward: list[tuple[str, str]] = []
    has_incoming = {target for _, target in edges}
    # Start from boxes nothing points to, so publishers come first and cycles break late.
    roots = [b for b in boxes if b not in has_incoming] + [b for b in boxes if b in has_incoming]
    for root in roots:
        if root in state:
            continue
        stack = [(root, iter(successors[root]))]
        state[root] = 1
        while stack:
            box, children = stack[-1]
            child = next(children, None)
            if child is None:
                state[box] = 2
                stack.pop()
            elif child not in state:
                forward.append((box, child))
                state[child] = 1
                stack.append((child, iter(successors[child])))
            elif state[child] == 2:
                forward.append((box, child))
            # state 1: a back edge, left out of the layering
    predecessors: dict[str, list[str]] = {box: [] for box in boxes}
    for source, target in forward:
        predecessors[target].append(source)
    layer: dict[str, int] = {}

    def depth(box: str) -> int:
        # Iterative memoised longest path (the forward edges form a DAG).
        pending = [box]
        while pending:
            current = pending[-1]
            missing = [p for p in predecessors[current] if p not in layer]
            if missing:
                pending += missing
                continue
            pending.pop()
            layer[current] = max((layer[p] + 1 for p in predecessors[current]), default=0)
        return layer[box]

    for box in boxes:
        depth(box)
    return layer


def _order(columns: list[list[str]], edges: list[tuple[str, str]]) -> None:
    """Reorder each column by the mean position of its neighbours (fewer crossings)."""
    neighbours: dict[str, list[str]] = {}
    for source, target in edges:
        neighbours.setdefault(source, []).append(target)
        neighbours.setdefault(target, []).append(source)
    for sweep in range(ORDERING_SWEEPS):
        indices = range(1, len(columns)) if sweep % 2 == 0 else range(len(columns) - 2, -1, -1)
        for index in indices:
            reference = columns[index - 1] if sweep % 2 == 0 else columns[index + 1]
            position = {box: i for i, box in enumerate(reference)}
            current = {box: i for i, box in enumerate(columns[index])}

            def barycenter(box: str, position: dict[str, int] = position,
                           current: dict[str, int] = current) -> float:
                placed = [position[n] for n in neighbours.get(box, ()) if n in position]
                return sum(placed) / len(placed) if placed else float(current[box])
            columns[index].sort(key=barycenter)


def box_width(label: str) -> float:
    return round(BOX_PADDING + CHAR_WIDTH * len(label), 1)


def layout(model: GraphModel) -> dict:
    """The model as the page draws it: boxes with kind and geometry, edges, overall size."""
    boxes = [*model.nodes, *model.topics]
    layer = _layers(boxes, model.edges)
    columns: list[list[str]] = [[] for _ in range(max(layer.values(), default=-1) + 1)]
    for box in boxes:
        columns[layer[box]].append(box)
    _order(columns, model.edges)
    tallest = max((len(c) for c in columns), default=0)
    height = tallest * (BOX_HEIGHT + ROW_GAP) + ROW_GAP
    placed = []
    x = float(COLUMN_GAP) / 2
    for column in columns:
        width = max(box_width(box) for box in column)
        top = (height - len(column) * (BOX_HEIGHT + ROW_GAP) + ROW_GAP) / 2
        for row, box in enumerate(column):
            kind = 'topic' if box in model.topics else 'node'
            placed.append({
                'id': box, 'kind': kind, 'types': model.topics.get(box, []), 'layer': layer[box],
                'x': round(x + (width - box_width(box)) / 2, 1),
                'y': round(top + row * (BOX_HEIGHT + ROW_GAP), 1),
                'width': box_width(box), 'height': BOX_HEIGHT})
        x += width + COLUMN_GAP
    return {
        'nodes': model.nodes,
        'topics': [{'name': t, 'types': types} for t, types in model.topics.items()],
        'edges': [{'from': s, 'to': t} for s, t in model.edges],
        'boxes': placed,
        'width': round(x - COLUMN_GAP / 2, 1) if columns else 0,
        'height': height if columns else 0,
    }
