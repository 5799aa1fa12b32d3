"""situated's HTTP service and command line.

``api.app.create_app(settings)`` builds the FastAPI application (nothing is built at import time);
``api.cli.main`` is the ``situated`` command. Routes are thin over the ``kb`` and ``dialogue``
libraries: parse the request, call the library off the event loop, shape the answer.
"""
