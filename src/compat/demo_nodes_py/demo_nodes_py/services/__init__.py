"""Services: add_two_ints (server, clients) and the service introspection demo."""
