"""What ament's linters share: the `linter` pytest marker, the file search and the ruff runner."""
