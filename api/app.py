"""The application factory: ``create_app(settings, kb=None, model=None)``.

Nothing is built at import time. The lifespan builds the services off the event loop (the KB,
its scene, the event hub) and stops them at shutdown; a KB passed in stays the caller's.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Callable, Sequence
from contextlib import asynccontextmanager

from fastapi import FastAPI
from fastapi.middleware.cors import CORSMiddleware
from fastapi_offline import FastAPIOffline
from starlette.concurrency import run_in_threadpool

from api.errors import install_error_handlers
from api.forward import WriterProxy
from api.limits import BodySizeLimit
from api.routes import dialogue, events, health, intents, locales, people, rasa, scene, sparql, turns, viewer
from api.routes import kb as kb_routes
from api.routes.health import package_version
from api.services import Services, start_services
from api.settings import Settings
from api.validtext import ValidText
from dialogue.llm.base import ChatModel
from kb import KB

DESCRIPTION = """Knowledge-grounded dialogue for social robots: a knowledge_core-compatible KB,
a SPARQL 1.1 endpoint, KB events (SSE, WebSocket) and a dialogue endpoint returning ROS4HRI intents.
Errors always have the shape `{"status", "code", "message", "details"}`."""

#: Another front of the same service in the same process (the ROS 2 node): started with the
#: services and the app's event loop once they are built (blocking work: run off the loop), it
#: returns what stops it, called before the services stop.
Extension = Callable[[Services, asyncio.AbstractEventLoop], Callable[[], None]]


def create_app(settings: Settings | None = None, kb: KB | None = None,
               model: ChatModel | None = None, extensions: Sequence[Extension] = ()) -> FastAPI:
    """A new app. ``kb``: use this KB (not closed at shutdown); ``model``: a dialogue model
    instance to use instead of the one ``settings.llm`` names; ``extensions``: other fronts on
    the same services (the ROS 2 node)."""
    config = settings if settings is not None else Settings()

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        services = await run_in_threadpool(start_services, config, kb, model)
        app.state.services = services
        stops: list[Callable[[], None]] = []
        try:
            loop = asyncio.get_running_loop()
            for extension in extensions:
                stops.append(await run_in_threadpool(extension, services, loop))
            yield
        finally:
            try:
                for stop in reversed(stops):
                    await run_in_threadpool(stop)
            finally:
                await services.aclose()

    # /docs must work offline: Swagger UI's script, style and icon come from fastapi-offline's
    # package (under /static-offline-docs), not from the CDN FastAPI's own page would load.
    app = FastAPIOffline(title="situated", version=package_version(), description=DESCRIPTION,
                         lifespan=lifespan, docs_url="/docs", redoc_url=None)
    install_error_handlers(app)
    if config.writer_url is not None:  # a reader: the scene and the commit feed are the writer's
        app.add_middleware(WriterProxy, writer_url=config.writer_url)
    app.add_middleware(ValidText)  # invalid Unicode in the URL or body: 400 before any route
    app.add_middleware(BodySizeLimit, max_bytes=config.limits.max_body_bytes)  # outermost
    if config.cors_origins:
        app.add_middleware(CORSMiddleware, allow_origins=config.cors_origins,
                           allow_methods=["GET", "POST", "DELETE"],
                           allow_headers=["Authorization", "Content-Type", "Accept"],
                           expose_headers=["X-Situated-Turn"])
    for router in (dialogue.router, kb_routes.router, sparql.router, events.router, rasa.router,
                   scene.router, health.router, intents.router, people.router, viewer.router, turns.router,
                   locales.router):
        app.include_router(router)
    app.mount(viewer.ASSETS_PATH, viewer.assets(), name="viewer-assets")
    return app
