"""owl_cli: the `owl` command, one subpackage per command (check, network, windows, pages, classroom)."""
