"""`owl windows`: the windows of programs without a display, served as one local page."""
