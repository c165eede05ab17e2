"""The checks of `owl check`, one module per course section.

Each module is a plug-in: setup.py's owl_cli.exercises entry points list them.
"""
