"""Regenerate the README's viewer screenshot: ``python -m tests.e2e.screenshot docs/viewer.png``.

Serves the app with the test kitchen plus a few more facts, expands some concepts, runs a query
and has a short chat, then saves a 1440x900 PNG.
"""

from __future__ import annotations

import sys
from pathlib import Path

import httpx
from playwright.sync_api import sync_playwright

from api.app import create_app
from api.server import serve_in_thread
from api.settings import Settings
from tests.e2e.conftest import CHROMIUM, CHROMIUM_ARGS, SCENE

EXTRA = [
    "book_1 rdf:type dbr:Book", "book_1 rdfs:label \"cookbook\"", "book_1 isOn table_1", "myself sees book_1",
    "person_tom rdf:type Human", "person_tom rdfs:label \"Tom\"", "person_tom isIn kitchen",
    "person_alice sees cup_1", "myself isIn kitchen",
]


def main(out: Path) -> None:
    app = create_app(Settings(scene=str(SCENE)))
    with serve_in_thread(app) as url, sync_playwright() as playwright:
        httpx.post(url + "/kb/revise", json={"statements": EXTRA, "method": "add"}).raise_for_status()
        browser = playwright.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        page = browser.new_page(viewport={"width": 1440, "height": 900})
        page.goto(url + "/")
        page.wait_for_selector('.node.expanded[data-id="myself"]')
        for term in ("table_1", "kitchen", "myself"):
            page.locator(f'.node[data-id="{term}"]').click()
            page.wait_for_selector(f'.node.expanded[data-id="{term}"]')
        page.fill("#patterns", "?h sees ?o\n?o rdf:type dbr:Cup")
        page.press("#patterns", "Control+Enter")
        page.fill("#user-id", "person_alice")
        page.fill("#chat-input", "pick up the cup")
        page.press("#chat-input", "Enter")
        page.wait_for_selector(".msg.robot:not(.waiting)")
        page.fill("#chat-input", "bring me the book")
        page.press("#chat-input", "Enter")
        page.locator(".msg.robot:not(.waiting)").nth(1).wait_for()
        second_cup = ["cup_2 rdf:type dbr:Cup", "cup_2 isOn table_1", "myself sees cup_2"]
        httpx.post(url + "/kb/revise", json={"statements": second_cup, "method": "add"}).raise_for_status()
        page.fill("#chat-input", "grab the cup")
        page.press("#chat-input", "Enter")
        page.wait_for_selector(".msg.robot.question")
        page.wait_for_timeout(3500)  # let the layout settle
        page.screenshot(path=str(out))
        browser.close()


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "docs/viewer.png"))
