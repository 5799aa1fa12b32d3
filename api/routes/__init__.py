"""The service's routers, one per concern; each handler parses, calls the library, shapes."""
