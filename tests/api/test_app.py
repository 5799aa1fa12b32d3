"""The factory: nothing at import time, OpenAPI docs, every documented route present."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from tests.api.conftest import Live

ROUTES = {
    ("/kb/query", "post"), ("/kb/query", "get"), ("/kb/revise", "post"), ("/kb/details/{term}", "get"),
    ("/kb/label/{term}", "get"), ("/kb/lookup", "get"), ("/kb/about/{term}", "get"),
    ("/kb/classesof/{term}", "get"), ("/kb/load", "post"), ("/kb/export", "get"), ("/kb/clear", "post"),
    ("/kb/events", "get"), ("/sparql", "get"), ("/sparql", "post"), ("/dialogues", "post"),
    ("/dialogues/{dialogue_id}/interactions", "post"), ("/dialogues/{dialogue_id}", "delete"),
    ("/webhooks/rest/webhook", "post"), ("/webhooks/rest/", "get"), ("/model/parse", "post"),
    ("/health", "get"), ("/version", "get"),
}


def test_importing_the_package_builds_nothing() -> None:
    code = ("import gc, api, api.app, api.cli; from fastapi import FastAPI; "
            "assert not [o for o in gc.get_objects() if isinstance(o, FastAPI)]")
    subprocess.run([sys.executable, "-c", code], check=True, cwd=Path(__file__).parents[2])


def test_openapi_lists_every_route_and_docs_are_served(live: Live) -> None:
    spec = live.client.get("/openapi.json").json()
    found = {(path, method) for path, item in spec["paths"].items() for method in item}
    assert found >= ROUTES
    docs = live.client.get("/docs")
    assert docs.status_code == 200 and "swagger" in docs.text.lower()
