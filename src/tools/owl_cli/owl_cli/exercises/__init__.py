"""The checks of `owl check`, one module per course section (plug-ins: setup.py's
owl_cli.exercises entry points list them).
"""
