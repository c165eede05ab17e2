"""`owl pages`: the front door and every page of the kit."""
