"""The windows folder of programs without a display (owl_windows.folder)."""
