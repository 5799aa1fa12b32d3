"""The viewer shows facts learnt from dialogue apart from perception's, with who told them and when
(headless Chromium against the real service, as tests/e2e/test_viewer.py)."""

from __future__ import annotations

import re
from typing import Any

from playwright.sync_api import expect

from tests.e2e.conftest import Opener, Service


def chat(page: Any, speaker: str, text: str) -> str:
    page.fill("#user-id", speaker)
    page.fill("#chat-input", text)
    page.press("#chat-input", "Enter")
    replies = page.locator(".msg.robot:not(.waiting) .reply")
    expect(replies).to_have_count(page.locator(".msg.user").count())
    reply: str = replies.last.inner_text()
    return reply


def test_a_fact_told_in_the_chat_is_drawn_and_listed_as_told(service: Service, open_viewer: Opener) -> None:
    page, watch = open_viewer(service)
    page.locator('.node[data-id="cup_1"]').wait_for()
    assert chat(page, "person_alice", "the cup is mine") == "OK, the cup is yours."
    told = page.locator('.edge[data-s="cup_1"][data-p="belongsTo"][data-o="person_alice"]')
    told.wait_for()
    expect(told).to_have_class(re.compile(r"\btold\b"))
    # Perception's facts keep their look.
    expect(page.locator('.edge[data-s="cup_1"][data-p="isOn"][data-o="table_1"]')).not_to_have_class(
        re.compile(r"\btold\b"))
    # No node for the provenance record itself: it is shown as the fact's provenance.
    expect(page.locator('.node[data-id^="told_"]')).to_have_count(0)

    page.locator('.node[data-id="cup_1"]').click()
    expect(page.locator("#concept-label")).to_have_text("cup_1")
    row = page.locator("#facts tbody tr.told", has_text="belongsTo")
    expect(row).to_have_attribute("data-told-by", "person_alice")
    expect(row.locator(".tag.told")).to_contain_text("told by person_alice")
    assert page.locator("#facts tbody tr", has_text="rdf:subject").count() == 0
    expect(page.locator("#facts tbody tr", has_text="isOn")).not_to_have_class(re.compile(r"\btold\b"))
    assert watch.errors == []


def test_a_name_told_in_the_chat_shows_on_the_persons_facts(service: Service, open_viewer: Opener) -> None:
    page, watch = open_viewer(service)
    assert chat(page, "user", "Hi, I'm Bob") == "Hello! Nice to meet you, Bob."
    page.fill("#goto-term", "user")
    page.press("#goto-term", "Enter")
    expect(page.locator("#concept-label")).to_have_text("Bob")
    told = page.locator(".concept-head .tag.told")
    expect(told).to_have_attribute("data-told-by", "user")
    expect(told).to_contain_text('name "Bob" told by user')
    assert watch.errors == []
