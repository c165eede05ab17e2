"""The `doctor` and `wtf` commands."""
