"""demo_nodes_cpp's executables, in Python: demo_nodes_py's nodes with the C++ demos' log lines."""
