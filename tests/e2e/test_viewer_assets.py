"""The viewer's files as the service serves them (no browser needed): every asset the page loads
is served from the package with its type, nothing refers to another host, and the error shape holds."""

from __future__ import annotations

import re

import pytest

from tests.e2e.conftest import Service

LOCAL_REF = re.compile(r"""(?:src|href)="([^"#][^"]*)"|from\s+"([^"]+)"|import\s+"([^"]+)\"""")


def referenced(text: str) -> set[str]:
    return {next(g for g in m.groups() if g) for m in LOCAL_REF.finditer(text)}


@pytest.mark.parametrize("path", ["/", "/viewer"])
def test_the_page_is_served_at_root_and_viewer(service: Service, path: str) -> None:
    response = service.client.get(path)
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/html")
    assert "default-src 'self'" in response.headers["content-security-policy"]
    assert "<title>situated" in response.text


def test_every_asset_the_page_uses_is_served_locally(service: Service) -> None:
    seen: set[str] = set()
    todo = ["/"]
    types = {".js": "text/javascript", ".css": "text/css", "/": "text/html"}
    while todo:
        path = todo.pop()
        response = service.client.get(path)
        assert response.status_code == 200, path
        suffix = "/" if path == "/" else path[path.rfind("."):]
        assert response.headers["content-type"].startswith(types[suffix]), path
        for ref in referenced(response.text):
            if ref.startswith("data:"):
                continue
            assert not re.match(r"^[a-z]+://", ref), f"{path} refers to another host: {ref}"
            absolute = ref if ref.startswith("/") else "/viewer/assets/" + ref.removeprefix("./")
            if absolute not in seen:
                seen.add(absolute)
                todo.append(absolute)
    assert {"/viewer/assets/app.js", "/viewer/assets/graph.js", "/viewer/assets/viewer.css"} <= seen


@pytest.mark.parametrize("name", ["nothing.js", "index.py", ".hidden.css", "..%2F..%2Fapp.py", "viewer"])
def test_unknown_assets_are_404_in_the_error_shape(service: Service, name: str) -> None:
    response = service.client.get(f"/viewer/assets/{name}")
    assert response.status_code == 404
    body = response.json()
    assert body["status"] == 404 and body["code"] == "not_found" and body["message"]
