"""What the verbs of `ros2 node` (and `ros2 param`) share (upstream's ros2node.api): node names."""

from owl_common.graph import full_node_name, is_hidden_node

from ros2cli.node.graph import Graph


def node_names(graph: Graph, include_hidden: bool = False) -> list[str]:
    """Full names of the nodes in the graph, sorted, duplicates kept."""
    names = [full_node_name(ns, name) for name, ns in graph.node_names_and_namespaces()]
    return sorted(n for n in names if include_hidden or not is_hidden_node(n))
