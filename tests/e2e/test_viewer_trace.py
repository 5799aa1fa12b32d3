"""The chat panel shows each reply's trace (issue 16): expand a reply, see who answered, the prompt
and JSON schema sent, the raw answers, the validation error and the repair, and the stage times."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import ExitStack
from typing import Any

import httpx
import pytest
from playwright.sync_api import expect

from api.app import create_app
from api.server import serve_in_thread
from api.settings import Settings
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.testing import ScriptedModel
from tests.e2e.conftest import SCENE, Opener, Service

GRAB = {"verbal_ack": "I will take the cup.", "user_intent": {"type": "__intent_grab_object__", "object": "cup_1",
                                                               "recipient": None, "goal": None, "input": None}}


@pytest.fixture
def hybrid_service() -> Iterator[Service]:
    """The service with the rules in front of a scripted model whose first answer is invalid."""
    model = HybridModel(ScriptedModel(['{"verbal_ack": "Hm", "user_intent": {"type": "__intent_dance__"}}', GRAB]))
    with ExitStack() as stack:
        url = stack.enter_context(serve_in_thread(create_app(Settings(scene=str(SCENE)), model=model)))
        client = stack.enter_context(httpx.Client(base_url=url, timeout=10))
        yield Service(url, client)


def send(page: Any, text: str) -> Any:
    count = page.locator(".msg.robot:not(.waiting)").count()
    page.fill("#chat-input", text)
    page.press("#chat-input", "Enter")
    reply = page.locator(".msg.robot:not(.waiting)").nth(count)
    reply.wait_for()
    return reply


def test_expanding_a_reply_shows_its_trace(hybrid_service: Service, open_viewer: Opener) -> None:
    page, watch = open_viewer(hybrid_service)
    page.fill("#user-id", "person_alice")
    rules = send(page, "pick up the cup")
    model = send(page, "zorglub the mug, snatch it")
    expect(model.locator(".reply")).to_have_text("I will take the cup.")

    model.locator("details.trace > summary").click()
    body = model.locator(".trace-body")
    body.wait_for()
    expect(body.locator(".trace-answered-by")).to_have_text("model")
    expect(body.locator(".trace-who")).to_contain_text("scripted")
    expect(body.locator(".trace-who")).to_contain_text("repaired")
    exchanges = body.locator(".trace-exchange")
    expect(exchanges).to_have_count(2)
    expect(exchanges.nth(0).locator(".trace-raw")).to_contain_text("__intent_dance__")
    expect(exchanges.nth(0).locator(".trace-error")).to_contain_text("__intent_dance__")
    expect(exchanges.nth(1)).to_have_attribute("data-repair", "true")
    expect(exchanges.nth(1).locator(".trace-raw")).to_contain_text("cup_1")
    # The prompt and the schema sent are there, folded.
    exchanges.nth(0).locator("summary", has_text="prompt messages").click()
    system = exchanges.nth(0).locator(".trace-message.role-system")
    expect(system.first).to_contain_text("You are")
    # Alice spoke a turn before: the model is told so in a system note (her memory, issue 17).
    expect(system.nth(1)).to_contain_text("You last spoke with [person_alice]")
    expect(exchanges.nth(0).locator(".trace-message.role-user").last).to_contain_text("snatch it")
    exchanges.nth(0).locator("summary", has_text="JSON schema sent").click()
    expect(exchanges.nth(0).locator("pre.json").first).to_contain_text('"user_intent"')
    for stage in ("ground", "model", "validate", "total"):
        expect(body.locator(f'.trace-stages li[data-stage="{stage}"]').first).to_be_visible()
    expect(body.locator(".trace-snapshot")).to_contain_text("person_alice")

    rules.locator("details.trace > summary").click()
    expect(rules.locator(".trace-answered-by")).to_have_text("rules")
    expect(rules.locator(".trace-exchange")).to_have_count(0)
    assert watch.errors == []
