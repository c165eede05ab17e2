"""`owl network`: the way from this machine to the Olive modules, and `--kit`'s end-to-end check."""
