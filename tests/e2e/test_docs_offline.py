"""The API documentation at /docs in headless Chromium with the network closed: every request to
anything but this machine's loopback is refused, and Swagger UI must still render the operations
(its scripts, styles and icon come from the installed package, not from a CDN)."""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any
from urllib.parse import urlsplit

import pytest

from tests.e2e.conftest import Service

LOOPBACK = {"127.0.0.1", "localhost", "::1", "[::1]"}


@pytest.fixture
def offline_page(browser: Any) -> Iterator[tuple[Any, list[str]]]:
    """A page whose every non-loopback request is aborted (and recorded)."""
    refused: list[str] = []

    def gate(route: Any) -> None:
        url = route.request.url
        if url.startswith("data:") or urlsplit(url).hostname in LOOPBACK:
            route.continue_()
        else:
            refused.append(url)
            route.abort("internetdisconnected")

    context = browser.new_context(viewport={"width": 1280, "height": 900})
    context.route("**/*", gate)
    page = context.new_page()
    page.set_default_timeout(15000)
    yield page, refused
    context.close()


def test_swagger_ui_renders_the_operations_with_the_network_closed(
        service: Service, offline_page: tuple[Any, list[str]]) -> None:
    page, refused = offline_page
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(service.url + "/docs")
    page.wait_for_selector("#swagger-ui .opblock")
    paths = {p.strip().replace("\u200b", "") for p in page.locator(".opblock-summary-path").all_inner_texts()}
    assert {"/kb/query", "/kb/revise", "/dialogues/{dialogue_id}/interactions", "/health"} <= paths
    assert page.locator(".opblock-post").count() > 0
    # The title block shows the service's own description: the OpenAPI document was read.
    assert "situated" in page.locator("#swagger-ui .info .title").inner_text()
    assert refused == [], f"/docs tried to reach other hosts: {refused}"
    assert errors == []


def test_every_asset_of_the_docs_page_is_served_by_the_service(service: Service) -> None:
    page = service.client.get("/docs")
    assert page.status_code == 200
    refs = re.findall(r"""(?:src|href)=["']([^"']+)["']""", page.text)
    assert len(refs) == 3  # script, style sheet, icon
    kinds = {".js": "text/javascript", ".css": "text/css", ".png": "image/png"}
    for ref in refs:
        assert ref.startswith("/"), f"/docs refers to another host: {ref}"
        asset = service.client.get(ref)
        assert asset.status_code == 200, ref
        assert asset.headers["content-type"].startswith(kinds[ref[ref.rfind("."):]]), ref
        assert len(asset.content) > 1000, ref
