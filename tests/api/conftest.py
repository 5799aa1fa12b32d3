"""A real uvicorn server on a free loopback port, in a background thread, for end-to-end tests."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import httpx
import pytest

from api.app import create_app
from api.server import serve_in_thread
from api.settings import Settings

SCENE = Path(__file__).with_name("scene.txt")


class Live:
    def __init__(self, url: str, app: Any) -> None:
        self.url = url
        self.app = app
        self.client = httpx.Client(base_url=url, timeout=60)  # generous: a busy machine

    @property
    def ws_url(self) -> str:
        return "ws" + self.url[len("http"):]

    @property
    def services(self) -> Any:
        return self.app.state.services


@contextmanager
def serve(app: Any) -> Iterator[Live]:
    with serve_in_thread(app) as url:
        live = Live(url, app)
        try:
            yield live
        finally:
            live.client.close()


def scene_settings(**values: Any) -> Settings:
    return Settings(scene=SCENE, **values)


@pytest.fixture
def live_factory() -> Iterator[Callable[..., Live]]:
    """Start servers with given settings (and kb/model); all are stopped after the test."""
    stack: list[Any] = []

    def start(settings: Settings | None = None, **kwargs: Any) -> Live:
        manager = serve(create_app(settings or scene_settings(), **kwargs))
        stack.append(manager)
        return manager.__enter__()

    yield start
    for manager in reversed(stack):
        manager.__exit__(None, None, None)


@pytest.fixture
def live(live_factory: Callable[..., Live]) -> Live:
    return live_factory()
