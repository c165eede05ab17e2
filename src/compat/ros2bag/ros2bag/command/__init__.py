"""The `bag` command."""
