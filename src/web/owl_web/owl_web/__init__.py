"""The server layer of Owl Kit Lab's browser pages (see README.md)."""
