"""olive_launch holds launch files only (see launch/)."""
