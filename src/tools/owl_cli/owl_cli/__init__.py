"""owl_cli: the `owl` command (owl network, owl windows, owl check) and owl check's exercises."""
