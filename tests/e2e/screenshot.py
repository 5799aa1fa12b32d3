"""Regenerate the README's viewer screenshot: ``python -m tests.e2e.screenshot docs/viewer.png``.

Serves the app exactly as ``situated serve`` does by default (the packaged demo scene, the rules
backend), expands a few concepts, runs a query and has a ten-turn chat, then saves a 1400x900 PNG.
"""

from __future__ import annotations

import sys
from pathlib import Path

from playwright.sync_api import sync_playwright

from api.app import create_app
from api.server import serve_in_thread
from api.settings import Settings
from tests.e2e.conftest import CHROMIUM, CHROMIUM_ARGS

#: The chat's ten turns, as a first conversation with the demo scene goes.
CHAT = ("hello", "what do you see?", "where is the apple?", "pick up the cup", "bring me the apple",
        "what can you do?", "who do you see?", "follow me", "tell me a joke", "thank you")  # fmt: skip


def main(out: Path) -> None:
    app = create_app(Settings())  # the defaults of `situated serve`: the demo scene, rules
    with serve_in_thread(app) as url, sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        page.goto(url + "/")
        page.wait_for_selector('.node.expanded[data-id="myself"]')
        for term in ("table", "living_room", "myself"):
            page.locator(f'.node[data-id="{term}"]').click()
            page.wait_for_selector(f'.node.expanded[data-id="{term}"]')
        page.fill("#patterns", "?h sees ?o\n?o rdf:type dbr:Cup")
        page.press("#patterns", "Control+Enter")
        page.wait_for_selector('#query-status[data-kind="ok"]')
        page.fill("#user-id", "person_alice")
        for turn, text in enumerate(CHAT):
            page.fill("#chat-input", text)
            page.press("#chat-input", "Enter")
            page.locator(".msg.robot:not(.waiting)").nth(turn).wait_for()
        page.wait_for_timeout(3500)  # let the layout settle
        page.screenshot(path=str(out))
        browser.close()


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "docs/viewer.png"))
