"""Small pieces every Owl Kit Lab node shares: running a node, calling a service once."""
