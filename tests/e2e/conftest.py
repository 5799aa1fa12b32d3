"""The viewer in a real browser: the service under uvicorn on a loopback port, Debian's Chromium
driven headless by Playwright. A test that drives the browser is marked `browser` and skipped where
/usr/bin/chromium is absent (here, not in each module)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import ExitStack
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx
import pytest

from api.app import create_app
from api.server import serve_in_thread
from api.settings import Settings

CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync"]
SCENE = Path(__file__).with_name("scene.txt")


@pytest.hookimpl(tryfirst=True)  # before `-m "not browser"` deselects by the marks
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if "browser" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.browser)
            if not CHROMIUM.exists():
                item.add_marker(pytest.mark.skip(reason=f"{CHROMIUM} is not installed (apt-get install "
                                                        "chromium); the browser tests need it"))


@dataclass
class Service:
    url: str
    client: httpx.Client
    token: str | None = None

    def revise(self, statements: list[str], method: str = "add") -> None:
        headers = {"Authorization": f"Bearer {self.token}"} if self.token else {}
        response = self.client.post("/kb/revise", json={"statements": statements, "method": method},
                                    headers=headers)
        response.raise_for_status()


@dataclass
class PageWatch:
    """What the page did that it should not: console errors, uncaught exceptions, foreign requests."""

    origin: str
    errors: list[str] = field(default_factory=list)
    foreign: list[str] = field(default_factory=list)

    def on_request(self, request: Any) -> None:
        url: str = request.url
        if not (url.startswith(self.origin + "/") or url.startswith("data:")):
            self.foreign.append(url)


# Module scope: the sync Playwright API keeps an event loop running in this thread while open,
# which would break asyncio.run() in the tests collected after these.
@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS,
                                              headless=True)
        yield chromium
        chromium.close()


@pytest.fixture
def start_service() -> Iterator[Callable[..., Service]]:
    """Start the real app (scene loaded, offline rules backend) with given settings."""
    with ExitStack() as stack:
        def start(**values: Any) -> Service:
            settings = Settings(scene=str(SCENE), **values)
            url = stack.enter_context(serve_in_thread(create_app(settings)))
            client = stack.enter_context(httpx.Client(base_url=url, timeout=10))
            token = settings.token.get_secret_value() if settings.token else None
            return Service(url, client, token)

        yield start


@pytest.fixture
def service(start_service: Callable[..., Service]) -> Service:
    return start_service()


#: Opens the viewer of a service: the page and what it did that it should not (`open_viewer`).
Opener = Callable[[Service], tuple[Any, PageWatch]]


@pytest.fixture
def open_viewer(browser: Any) -> Iterator[Opener]:
    """Open the viewer of a service in a fresh browser context; check the page stayed clean."""
    contexts: list[Any] = []
    watches: list[PageWatch] = []

    def open_page(service: Service) -> tuple[Any, PageWatch]:
        context = browser.new_context(viewport={"width": 1440, "height": 900})
        contexts.append(context)
        page = context.new_page()
        page.set_default_timeout(30_000)  # generous: a busy machine
        watch = PageWatch(service.url)
        watches.append(watch)
        page.on("console", lambda msg: watch.errors.append(msg.text) if msg.type == "error" else None)
        page.on("pageerror", lambda exc: watch.errors.append(str(exc)))
        page.on("request", watch.on_request)
        page.goto(service.url + "/")
        page.wait_for_selector('#live[data-state="live"]')
        page.wait_for_selector('.node.expanded[data-id="myself"]')
        return page, watch

    yield open_page
    for context in contexts:
        context.close()
    for watch in watches:
        assert watch.foreign == [], f"the page fetched from elsewhere: {watch.foreign}"
