"""The Rasa-compatible facade: REST channel webhook and /model/parse shapes."""

from __future__ import annotations

from collections.abc import Callable

import httpx
from pydantic import SecretStr

from api.rasa import parse_result, webhook_messages
from api.settings import Settings
from dialogue.intents import Intent
from tests.api.conftest import SCENE, Live


def test_webhook_reply_with_intents_in_custom(live: Live) -> None:
    assert live.client.get("/webhooks/rest/").json() == {"status": "ok"}
    messages = live.client.post("/webhooks/rest/webhook",
                                json={"sender": "person_alice", "message": "pick up the cookbook"}).json()
    assert isinstance(messages, list) and len(messages) == 1
    (message,) = messages
    assert message["recipient_id"] == "person_alice" and message["text"]
    (intent,) = message["custom"]["intents"]
    assert intent["intent"] == "__intent_grab_object__" and intent["data"] == {"object": "book_1"}
    assert intent["source"] == "person_alice"
    # the conversation is remembered per sender: "it" refers to the cookbook
    follow = live.client.post("/webhooks/rest/webhook", json={"sender": "person_alice", "message": "hello",
                                                              "metadata": {"x": 1}}).json()
    assert follow[0]["custom"]["intents"][0]["intent"] == "__intent_greet__"


def test_webhook_splits_at_blank_lines_and_omits_null_keys() -> None:
    intent = Intent(intent="__intent_greet__", data={"recipient": "p"}, source="p")
    assert webhook_messages("u", "Hi.\n\nHow are you?", [intent]) == [
        {"recipient_id": "u", "text": "Hi."},
        {"recipient_id": "u", "text": "How are you?", "custom": {"intents": [intent.model_dump()]}},
    ]
    assert webhook_messages("u", "", []) == []
    assert webhook_messages("u", "", [intent]) == [{"recipient_id": "u",
                                                    "custom": {"intents": [intent.model_dump()]}}]


def test_json_values_ride_in_custom_whole_and_are_entities_as_json_text() -> None:
    """An intent's non-entity roles may hold any JSON: the webhook's ``custom`` carries them as they
    are; a parse result's entity value is text (Rasa's), so such a role is its JSON there."""
    intent = Intent(intent="__intent_start_activity__", source="p",
                    data={"object": "quiz", "other_data": {"round": 3, "topics": ["art"]}})
    assert webhook_messages("u", "Let's play.", [intent])[0]["custom"]["intents"][0]["data"] == intent.data
    parsed = parse_result("start the quiz", [intent], lambda term: term)
    assert parsed["entities"] == [
        {"start": 10, "end": 14, "value": "quiz", "entity": "object", "confidence": 1.0},
        {"start": 0, "end": 0, "value": '{"round": 3, "topics": ["art"]}', "entity": "other_data",
         "confidence": 1.0}]


def test_model_parse_shape(live: Live) -> None:
    parsed = live.client.post("/model/parse", json={"text": "grab the cookbook"}).json()
    assert set(parsed) == {"text", "intent", "entities", "intent_ranking"}
    assert parsed["text"] == "grab the cookbook"
    assert set(parsed["intent"]) == {"name", "confidence"}
    assert parsed["intent"]["name"] == "__intent_grab_object__"
    assert 0 < parsed["intent"]["confidence"] <= 1
    (entity,) = parsed["entities"]
    assert entity["entity"] == "object" and entity["value"] == "book_1"
    assert "grab the cookbook"[entity["start"]:entity["end"]] == "cookbook"
    assert parsed["intent_ranking"][0]["name"] == "__intent_grab_object__"
    fallback = live.client.post("/model/parse", json={"text": "qwxz plorp"}).json()
    assert fallback["intent"]["name"] == "__raw_user_input__" and fallback["entities"] == []
    assert live.client.post("/model/parse", json={}).status_code == 422


def test_model_parse_takes_the_sender_as_the_speaker(live: Live) -> None:
    """Rasa's /model/parse request has no speaker (text, message_id); ours takes the webhook's
    `sender`, so "me" is someone: the recipient of "bring me the cookbook" is the sender."""
    def parse(**body: str) -> httpx.Response:
        return live.client.post("/model/parse", json={"text": "bring me the cookbook", **body})

    parsed = parse(sender="person_tom").json()
    assert parsed["intent"]["name"] == "__intent_bring_object__"
    assert {e["entity"]: e["value"] for e in parsed["entities"]} == {"object": "book_1", "recipient": "person_tom"}
    assert live.services.dialogues.ids() == ["default"]  # nothing recorded in a dialogue
    for thing in ("book_1", "myself", "rdf:type"):  # checked as any speaker, before anything is learnt
        refused = parse(sender=thing)
        assert (refused.status_code, refused.json()["code"]) == (400, "not_a_person"), thing
        assert "sender" in refused.json()["message"]
    assert parse(sender="").status_code == 422
    assert live.client.get("/kb/query", params={"pattern": "visitor_9 rdf:type ?c"}).json() == []
    assert {e["entity"]: e["value"] for e in parse(sender="visitor_9").json()["entities"]}["recipient"] == \
        "visitor_9"  # a sender the KB did not know is a person of it now, as the webhook's
    assert {"c": "Human"} in live.client.get("/kb/query", params={"pattern": "visitor_9 rdf:type ?c"}).json()


def test_rasa_style_token_parameter(live_factory: Callable[..., Live]) -> None:
    live = live_factory(Settings(scene=SCENE, token=SecretStr("rasa-secret")))
    message = {"sender": "u2", "message": "hello"}
    assert live.client.post("/webhooks/rest/webhook", json=message).status_code == 401
    assert live.client.post("/webhooks/rest/webhook?token=nope", json=message).status_code == 403
    ok = live.client.post("/webhooks/rest/webhook?token=rasa-secret", json=message)
    assert ok.status_code == 200 and ok.json()[0]["recipient_id"] == "u2"


def test_model_parse_follows_the_access_rule_of_dialogue_turns(live_factory: Callable[..., Live]) -> None:
    """It runs a turn (model requests, under a model backend): the token, as for an interaction."""
    live = live_factory(Settings(scene=SCENE, token=SecretStr("rasa-secret")))
    text = {"text": "pick up the cookbook"}
    assert live.client.post("/dialogues/default/interactions", json={"user_id": "u", "input": "hi"}).status_code == 401
    refused = live.client.post("/model/parse", json=text)
    assert refused.status_code == 401 and refused.json()["code"] == "unauthorized"
    assert live.client.post("/model/parse?token=nope", json=text).status_code == 403
    for allowed in (live.client.post("/model/parse?token=rasa-secret", json=text),
                    live.client.post("/model/parse", json=text, headers={"authorization": "Bearer rasa-secret"})):
        assert allowed.status_code == 200 and allowed.json()["intent"]["name"] == "__intent_grab_object__"


def test_a_blank_message_is_answered_with_no_message_and_parse_refuses_blank_text(live: Live) -> None:
    """Rasa answers a blank message 200 with no message; nothing is recorded, no dialogue made. The
    sender is still checked. /model/parse has nothing to parse in blank text: 422."""
    for text in ("", "  ", "\n"):
        answer = live.client.post("/webhooks/rest/webhook", json={"sender": "person_alice", "message": text})
        assert (answer.status_code, answer.json()) == (200, [])
        parsed = live.client.post("/model/parse", json={"text": text})
        assert parsed.status_code == 422 and "empty or blank" in parsed.json()["message"]
    assert "rasa:person_alice" not in live.services.dialogues.ids()
    thing = live.client.post("/webhooks/rest/webhook", json={"sender": "book_1", "message": ""})
    assert (thing.status_code, thing.json()["code"]) == (400, "not_a_person")
    assert live.client.post("/webhooks/rest/webhook", json={"sender": "person_alice"}).status_code == 422


def test_a_sender_the_kb_does_not_know_becomes_a_person_of_it(live: Live) -> None:
    """Every referent of an intent is a KB entity, the speaker included: a Rasa sender the KB has
    never heard of is a person of the KB after its first message, and only then named."""
    assert live.client.get("/kb/query", params={"pattern": "u rdf:type ?c"}).json() == []
    messages = live.client.post("/webhooks/rest/webhook", json={"sender": "u", "message": "hello"}).json()
    (intent,) = messages[-1]["custom"]["intents"]
    assert intent["intent"] == "__intent_greet__" and intent["data"] == {"recipient": "u"}
    people = live.client.get("/kb/query", params={"pattern": "?p rdf:type Human"}).json()
    assert {"p": "u"} in people
    # /model/parse without a sender has no speaker: nothing names one, and the KB gains nobody
    parsed = live.client.post("/model/parse", json={"text": "bring me the cookbook"}).json()
    assert all(entity["value"] != "__unknown_agent__" for entity in parsed["entities"])
    people_after = live.client.get("/kb/query", params={"pattern": "?p rdf:type Human"}).json()
    assert sorted(p["p"] for p in people_after) == sorted(p["p"] for p in people)
