"""The ask role end to end over HTTP (issue 16): the question as the opening line, several fields in
one answer, corrections, cancel, KB-entity fields with clarification, the rules and a scripted model."""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any

from api.settings import Settings
from dialogue.llm.testing import ScriptedModel
from tests.api.conftest import SCENE, Live

ALICE = "person_alice"
FORM = {"question": "How old are you, which cup do you want, and who should bring it?",
        "result_schema_properties": {"age": {"type": "integer", "minimum": 0, "maximum": 130},
                                     "cup": {"type": "string", "x-kb-class": "dbr:Cup"},
                                     "bringer": {"type": "string", "format": "kb-person", "title": "person"},
                                     "sugar": {"type": "boolean"}}}
TWO_CUPS = ["cup_1 hasColor red", "cup_2 rdf:type dbr:Cup", "cup_2 hasColor blue", "cup_2 isOn table_1",
            "myself sees cup_2"]


def start(live: Live, form: dict[str, Any] = FORM, **extra: Any) -> tuple[str, str]:
    started = live.client.post("/dialogues", json={"role": {"name": "__ask__", "configuration": json.dumps(form)},
                                                   **extra})
    assert started.status_code == 201, started.text
    body = started.json()
    return body["dialogue_id"], body["response"]


def say(live: Live, dialogue_id: str, text: str, **extra: Any) -> dict[str, Any]:
    reply = live.client.post(f"/dialogues/{dialogue_id}/interactions", json={"user_id": ALICE, "input": text, **extra})
    assert reply.status_code == 200, reply.text
    body: dict[str, Any] = reply.json()
    return body


def results(reply: dict[str, Any]) -> dict[str, Any]:
    value: dict[str, Any] = json.loads(reply["results"])
    return value


def test_the_rules_fill_a_form_with_clarification_and_correction(live: Live) -> None:
    live.client.post("/kb/revise", json={"statements": TWO_CUPS, "method": "add"}).raise_for_status()
    dialogue_id, question = start(live)
    assert question == FORM["question"]
    first = say(live, dialogue_id, "I'm thirty-four and I'd like a cup")
    assert results(first) == {"age": 34} and first["dialogue_terminal"] is False
    assert first["response"] == "Which cup do you mean: the red one or the blue one?" and first["intents"] == []
    second = say(live, dialogue_id, "the blue one, and Tom")
    assert results(second) == {"age": 34, "cup": "cup_2", "bringer": "person_tom"}
    assert second["response"] == "And sugar: yes or no?"
    third = say(live, dialogue_id, "no, I'm 35")  # both: no sugar, and a correction
    assert third["dialogue_terminal"] is True and third["response"] == "Thank you."
    assert results(third) == {"age": 35, "cup": "cup_2", "bringer": "person_tom", "sugar": False}


def test_cancel_ends_with_what_it_has(live: Live) -> None:
    dialogue_id, _ = start(live)
    say(live, dialogue_id, "42")
    cancelled = say(live, dialogue_id, "never mind")
    assert cancelled["dialogue_terminal"] is True and results(cancelled) == {"age": 42}
    assert cancelled["response"] == "OK, never mind."


def test_an_invalid_answer_is_said_back_and_asked_again(live: Live) -> None:
    dialogue_id, _ = start(live)
    reply = say(live, dialogue_id, "two hundred")
    assert reply["response"].startswith("That is not a possible age: it must be at least 0 and at most 130.")
    assert results(reply) == {} and reply["dialogue_terminal"] is False


def test_a_bad_configuration_is_refused(live: Live) -> None:
    refused = live.client.post("/dialogues", json={"role": {"name": "__ask__", "configuration": '{"question": 1}'}})
    assert (refused.status_code, refused.json()["code"]) == (400, "dialogue_error")
    assert "needs a question" in refused.json()["message"]


def test_a_scripted_model_fills_the_form(live_factory: Callable[..., Live]) -> None:
    model = ScriptedModel([
        {"answers": {"age": 34, "cup": "cup_1", "bringer": None, "sugar": None}, "cancel": False,
         "verbal_ack": "And who brings it?"},
        {"answers": {"bringer": "Tom", "sugar": True}, "cancel": False, "verbal_ack": "Thanks!"},
    ])
    live = live_factory(Settings(scene=SCENE), model=model)
    dialogue_id, _ = start(live)
    first = say(live, dialogue_id, "Thirty-four. The cup on the table.")
    assert results(first) == {"age": 34, "cup": "cup_1"}
    second = say(live, dialogue_id, "Tom will, with sugar please")
    assert second["dialogue_terminal"] is True
    assert results(second) == {"age": 34, "cup": "cup_1", "bringer": "person_tom", "sugar": True}
    schema = model.requests[0].schema["properties"]["answers"]["properties"]
    assert schema["cup"]["anyOf"][0] == {"enum": ["cup_1"]}
    assert set(schema["bringer"]["anyOf"][0]["enum"]) == {"person_alice", "person_tom"}


def test_a_configuration_json_cannot_carry_is_a_clear_400_and_the_dialogue_stays_readable(live: Live) -> None:
    """Once a 500 each: a 5,000-digit number, 10,000 levels of nesting, a lone surrogate (whose dialogue
    then answered 500 to every turn and to GET .../turns)."""
    good = json.dumps({"question": "How old?", "result_schema_properties": {"age": {"type": "integer"}}})
    bad = {"digits": good.replace('"integer"}', '"integer", "minimum": ' + "9" * 5000 + "}"),
           "nesting": good.replace('"integer"}', '"integer", "x": ' + "[" * 10_000 + "]" * 10_000 + "}"),
           "surrogate": good.replace("age", "a\\udc00ge")}
    for what, configuration in bad.items():
        role = {"name": "__ask__", "configuration": configuration}
        started = live.client.post("/dialogues", json={"role": role})
        assert (started.status_code, started.json()["code"]) == (400, "dialogue_error"), what
        stateless = live.client.post("/dialogues/default/interactions",
                                     json={"user_id": ALICE, "input": "33", "role": role})
        assert (stateless.status_code, stateless.json()["code"]) == (400, "dialogue_error"), what
        assert "configuration" in stateless.json()["message"] or "field" in stateless.json()["message"], what
    turns = live.client.get("/dialogues/default/turns")
    assert turns.status_code == 200 and turns.json()["turns"] == []  # nothing of them was kept
    assert say(live, "default", "hello")["response"]  # and the dialogue answers
