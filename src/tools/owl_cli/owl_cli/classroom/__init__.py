"""`owl class`: a class server on JupyterHub, one Unix account per student (docs/classroom.md)."""
