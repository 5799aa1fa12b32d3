"""Dialogue routes (chatbot_msgs shapes) end to end, with the rules backend and test models."""

from __future__ import annotations

import json

from api.settings import Limits, Settings
from dialogue.llm.base import ChatRequest
from dialogue.llm.testing import FunctionModel, ScriptedModel
from tests.api.conftest import SCENE, Live

INTENT_KEYS = {"intent", "data", "source", "modality", "priority", "confidence"}


def test_start_interact_end(live: Live) -> None:
    client = live.client
    started = client.post("/dialogues", json={"role": {"name": "__default__", "configuration": "{}"},
                                              "locale": "en_GB"})
    assert started.status_code == 201
    dialogue_id = started.json()["dialogue_id"]
    reply = client.post(f"/dialogues/{dialogue_id}/interactions",
                        json={"user_id": "person_alice", "input": "please pick up the cup"}).json()
    assert set(reply) == {"response", "intents", "error_msg"}
    assert reply["error_msg"] == "" and reply["response"]
    (intent,) = reply["intents"]
    assert set(intent) == INTENT_KEYS
    assert intent["intent"] == "__intent_grab_object__" and intent["data"] == {"object": "cup_1"}
    assert intent["source"] == "person_alice" and intent["priority"] == 128
    assert intent["modality"] == "__modality_speech__"
    ended = client.delete(f"/dialogues/{dialogue_id}")
    assert ended.status_code == 200 and ended.json() == {"dialogue_id": dialogue_id, "role": "__default__",
                                                          "locale": "en_GB", "status": "open", "results": "{}",
                                                          "error_msg": ""}
    gone = client.post(f"/dialogues/{dialogue_id}/interactions", json={"user_id": "a", "input": "hi"})
    assert (gone.status_code, gone.json()["code"]) == (404, "unknown_dialogue")


def test_a_caller_chooses_the_dialogue_id_once(live: Live) -> None:
    """As a ROS Dialogue goal's UUID is its dialogue's id, a REST caller may choose the id; an id
    in use is a 409 saying so, a bad one a 422 saying why, and neither changes anything."""
    client = live.client
    chosen = "0f8fad5b-d9cb-469f-a165-70867728950e"
    started = client.post("/dialogues", json={"dialogue_id": chosen, "role": {"name": "__ask__", "configuration":
                                              json.dumps({"question": "How old are you?", "result_schema_properties":
                                                          {"age": {"type": "integer"}}})}})
    assert started.status_code == 201 and started.json() == {"dialogue_id": chosen, "response": "How old are you?"}
    answer = client.post(f"/dialogues/{chosen}/interactions", json={"user_id": "person_alice", "input": "I'm 7"})
    assert answer.json()["results"] == '{"age": 7}'
    before = live.services.dialogues.ids()
    for taken in (chosen, "default"):
        again = client.post("/dialogues", json={"dialogue_id": taken})
        assert (again.status_code, again.json()["code"]) == (409, "dialogue_exists"), again.text
        assert f"dialogue {taken!r} already exists" in again.json()["message"]
    for bad in ("", "a/b", "with space", "-lead", "x" * 129, "ça", "a?b", "a#b"):
        refused = client.post("/dialogues", json={"dialogue_id": bad})
        assert refused.status_code == 422, bad
        assert "cannot be a dialogue's id: 1 to 128 characters" in refused.json()["message"]
    assert live.services.dialogues.ids() == before
    assert live.services.dialogues.get(chosen).role == "__ask__"  # the first one, untouched
    client.delete(f"/dialogues/{chosen}")
    assert client.post("/dialogues", json={"dialogue_id": chosen}).status_code == 201  # free again once ended
    assert client.post("/dialogues", json={"dialogue_id": "robot-3:hall_1.a"}).json()["dialogue_id"] == \
        "robot-3:hall_1.a"


def test_where_a_dialogue_is_and_how_it_ended_are_read_over_rest(live: Live) -> None:
    """What a ROS Dialogue goal's result says — the role's results, error_msg when the person called
    it off — REST reads from the same place: GET while it runs, and DELETE's answer when it ends."""
    client = live.client
    form = json.dumps({"question": "How old are you, and your name?", "result_schema_properties": {
        "age": {"type": "integer"}, "name": {"type": "string"}}})

    def ask() -> str:
        started = client.post("/dialogues", json={"role": {"name": "__ask__", "configuration": form}})
        dialogue_id: str = started.json()["dialogue_id"]
        return dialogue_id

    def turn(dialogue_id: str, text: str) -> None:
        client.post(f"/dialogues/{dialogue_id}/interactions", json={"user_id": "person_alice", "input": text})

    done, called_off, left = ask(), ask(), ask()
    assert client.get(f"/dialogues/{done}").json() == {"dialogue_id": done, "role": "__ask__", "status": "open",
                                                       "results": "{}", "error_msg": ""}
    turn(done, "I am 40 and my name is Alice")
    assert client.get(f"/dialogues/{done}").json() == {"dialogue_id": done, "role": "__ask__", "status": "done",
                                                       "results": '{"age": 40, "name": "Alice"}', "error_msg": ""}
    turn(called_off, "I'm 12")
    turn(called_off, "never mind")
    assert client.get(f"/dialogues/{called_off}").json() == {
        "dialogue_id": called_off, "role": "__ask__", "status": "cancelled", "results": '{"age": 12}',
        "error_msg": "the person called the dialogue off"}
    turn(left, "I'm 30")
    assert client.delete(f"/dialogues/{left}").json() == {"dialogue_id": left, "role": "__ask__", "status": "open",
                                                           "results": '{"age": 30}', "error_msg": ""}
    assert client.delete(f"/dialogues/{done}").json()["status"] == "done"
    for gone in (left, done):
        for answer in (client.get(f"/dialogues/{gone}"), client.delete(f"/dialogues/{gone}")):
            assert (answer.status_code, answer.json()["code"]) == (404, "unknown_dialogue")
    assert client.get("/dialogues/default").json() == {"dialogue_id": "default", "role": "__default__",
                                                       "status": "open", "results": "{}", "error_msg": ""}


def test_a_default_dialogue_is_done_when_the_person_takes_leave(live: Live) -> None:
    client = live.client
    dialogue_id = client.post("/dialogues", json={}).json()["dialogue_id"]

    def turn(text: str) -> dict[str, object]:
        answer: dict[str, object] = client.post(f"/dialogues/{dialogue_id}/interactions",
                                                json={"user_id": "person_alice", "input": text}).json()
        return answer

    bye = turn("goodbye robot")
    assert bye["dialogue_terminal"] is True and bye["intents"] == []
    assert client.get(f"/dialogues/{dialogue_id}").json()["status"] == "done"
    assert "dialogue_terminal" not in turn("hello again")  # talking again opens it
    assert client.get(f"/dialogues/{dialogue_id}").json()["status"] == "open"


def test_default_dialogue_always_exists_and_records_without_reply(live: Live) -> None:
    client = live.client
    recorded = client.post("/dialogues/default/interactions",
                           json={"user_id": "__assistant__", "input": "Hello!", "response_expected": False})
    assert recorded.json() == {"response": "", "intents": [], "error_msg": ""}
    assert client.delete("/dialogues/default").status_code == 200
    greeting = client.post("/dialogues/default/interactions", json={"user_id": "person_alice", "input": "hi"})
    assert greeting.json()["intents"][0]["intent"] == "__intent_greet__"


def test_unknown_input_falls_back_to_raw_user_input(live: Live) -> None:
    reply = live.client.post("/dialogues/default/interactions",
                             json={"user_id": "person_alice", "input": "zorglub frobnicate"}).json()
    assert reply["intents"][0]["intent"] == "__raw_user_input__"
    assert reply["intents"][0]["data"]["input"] == "zorglub frobnicate"


def test_bad_requests(live: Live) -> None:
    client = live.client
    assert client.post("/dialogues", json={"role": {"name": "__ask__"}}).json()["code"] == "dialogue_error"
    missing = client.post("/dialogues/default/interactions", json={"input": "hi"})
    assert missing.status_code == 422 and "user_id" in missing.json()["message"]


def test_history_limit(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = live_factory(Settings(scene=SCENE, limits=Limits(max_history_turns=2)))
    turns = [{"speaker": "person_alice", "text": "hi"}] * 3
    refused = live.client.post("/dialogues/default/interactions",
                               json={"user_id": "person_alice", "input": "hi", "history": turns})
    assert (refused.status_code, refused.json()["code"]) == (413, "too_many_history_turns")


def test_a_test_model_answer_is_validated_against_the_kb(live_factory) -> None:  # type: ignore[no-untyped-def]
    grab = "__intent_grab_object__"
    answers = [{"verbal_ack": "Taking it.", "user_intent": {"type": grab, "object": "cup_1"}},
               {"verbal_ack": "Taking it.", "user_intent": {"type": "__intent_grab_object__",
                                                            "object": "unicorn_9"}},
               {"verbal_ack": "Still no.", "user_intent": {"type": "__intent_grab_object__",
                                                           "object": "unicorn_9"}}]
    model = ScriptedModel(answers)
    live = live_factory(model=model)
    ok = live.client.post("/dialogues/default/interactions", json={"user_id": "person_alice",
                                                                   "input": "the thing, grab it"}).json()
    assert ok["intents"][0]["data"] == {"object": "cup_1"} and ok["response"] == "Taking it."
    invented = live.client.post("/dialogues/default/interactions", json={"user_id": "person_alice",
                                                                         "input": "grab the unicorn"}).json()
    assert all(i["data"].get("object") != "unicorn_9" for i in invented["intents"])
    assert len(model.requests) == 3  # one repair request after the invalid answer


def test_health_reports_the_model(live_factory) -> None:  # type: ignore[no-untyped-def]
    def answer(request: ChatRequest) -> str:
        return json.dumps({"verbal_ack": "ok", "user_intent": None})

    live = live_factory(model=FunctionModel(answer, name="fn"))
    health = live.client.get("/health").json()
    assert health["model"] == {"name": "fn", "remote": False, "reachable": True, "detail": "in-process"}
    assert health["kb"]["size"] > health["kb"]["asserted"] > 0
    assert live.client.get("/version").json()["name"] == "situated"


def test_an_empty_or_blank_input_is_nothing_said_no_answer_and_nothing_recorded(live: Live) -> None:
    """As over ROS (chatbot_msgs allows an empty input): a person who said nothing gets no answer,
    and nothing is recorded, traced or pushed; an empty system update still asks an ask dialogue."""
    client, dialogues = live.client, live.services.dialogues
    client.post("/dialogues/default/interactions", json={"user_id": "person_alice", "input": "hello"})
    history, pushed = dialogues.get("default").history, live.services.bus.last_seq
    traced = len(client.get("/dialogues/default/turns").json()["turns"])
    nothing = {"response": "", "intents": [], "error_msg": ""}
    for text in ("", "   ", "\n\t"):
        for expected in (True, False):
            answer = client.post("/dialogues/default/interactions", json={
                "user_id": "person_alice", "input": text, "response_expected": expected})
            assert (answer.status_code, answer.json()) == (200, nothing), answer.text
            assert "X-Situated-Turn" not in answer.headers
        stateless = client.post("/dialogues/dm-7/interactions", json={"role": {"name": "__default__"}, "history": [
            {"speaker": "person_alice", "text": "hello"}, {"speaker": "person_tom", "text": text}]})
        assert stateless.status_code == 200 and stateless.json()["response"] == "" and stateless.json()["intents"] == []
    assert dialogues.get("default").history == history and live.services.bus.last_seq == pushed
    assert len(client.get("/dialogues/default/turns").json()["turns"]) == traced
    form = json.dumps({"question": "How old are you?", "result_schema_properties": {"age": {"type": "integer"}}})
    asked = client.post("/dialogues", json={"role": {"name": "__ask__", "configuration": form}}).json()["dialogue_id"]
    prompt = client.post(f"/dialogues/{asked}/interactions", json={"user_id": "__system__", "input": ""})
    assert prompt.json()["response"] == "How old are you?"


def test_concurrent_turns_on_one_dialogue_each_answer_by_their_own_deadline(live_factory) -> None:  # type: ignore[no-untyped-def]
    """Twelve turns sent at once to `default` with a model that never answers: each is answered
    within one deadline (plus a generous margin) of when it was sent, not after the ones queued
    before it, and every one is recorded in the history."""
    import asyncio
    import time
    from concurrent.futures import ThreadPoolExecutor

    async def hang(request: ChatRequest) -> str:
        await asyncio.sleep(3600)
        raise AssertionError("the hanging model answered")

    deadline, margin, turns = 1.0, 4.0, 12
    live = live_factory(Settings(scene=SCENE, deadline=deadline), model=FunctionModel(hang, name="hanging"))

    def send(n: int) -> tuple[int, dict[str, object], float]:
        started = time.monotonic()
        response = live.client.post("/dialogues/default/interactions",
                                    json={"user_id": "person_alice", "input": f"fetch thing {n}"})
        return response.status_code, response.json(), time.monotonic() - started

    with ThreadPoolExecutor(turns) as pool:
        answers = list(pool.map(send, range(turns)))
    for status, reply, elapsed in answers:
        assert status == 200 and elapsed < deadline + margin, (reply, elapsed)
        assert [i["intent"] for i in reply["intents"]] == ["__raw_user_input__"]  # type: ignore[attr-defined]
    live.client.post("/dialogues/default/interactions",
                     json={"user_id": "person_alice", "input": "that is all", "response_expected": False})
    said = [u.text for u in live.services.dialogues.get("default").history if u.speaker == "person_alice"]
    assert sorted(said[:-1]) == sorted(f"fetch thing {n}" for n in range(turns)) and said[-1] == "that is all"


NOT_PEOPLE = {  # user id -> what the refusal says it names (tests/api/scene.txt)
    "cup_1": "names cup_1, a thing of the KB", "kitchen": "names the kitchen, a place of the KB",
    "myself": "names the robot itself", "dbr:Cup": "names a class of the KB", "Human": "names a class of the KB",
    "isOn": "names a property of the KB", "rdf:type": "is an RDF/OWL keyword", "owl:Thing": "is an RDF/OWL keyword",
}


def test_a_user_id_naming_what_is_no_person_is_refused_on_every_route(live: Live) -> None:
    """Any user id once became a person: `cup_1`, `dbr:Cup` or `Human` an agent, `rdf:type` a Human the
    robot greeted. Refused everywhere a speaker enters, and nothing changes."""
    client = live.client
    kb = live.services.kb
    revision, models = kb.revision, kb.models()
    for user, says in NOT_PEOPLE.items():
        calls = {
            "3.0": client.post("/dialogues/default/interactions", json={"user_id": user, "input": "I like tea"}),
            "recorded": client.post("/dialogues/default/interactions",
                                    json={"user_id": user, "input": "hello", "response_expected": False}),
            "4.0": client.post("/dialogues/default/interactions", json={
                "role": {"name": "__default__"}, "history": [{"speaker": user, "text": "hello"}]}),
            "rasa": client.post("/webhooks/rest/webhook", json={"sender": user, "message": "hello"}),
            "people": client.get(f"/people/{user}/memory"),
        }
        for route, answer in calls.items():
            assert (answer.status_code, answer.json()["code"]) == (400, "not_a_person"), (user, route, answer.text)
            message = answer.json()["message"]
            assert repr(user) in message and says in message and "not a person" in message, (route, message)
    assert kb.revision == revision and kb.models() == models  # nothing learnt, nobody added
    assert not any(d.startswith("rasa:") for d in live.services.dialogues.ids())
    assert client.get("/dialogues/default/turns").json()["turns"] == []
    # people, known or new, and the chat roles still speak
    for user in ("person_alice", "person_tom", "person_new", "__assistant__", "__unknown_agent__"):
        answer = client.post("/dialogues/default/interactions", json={"user_id": user, "input": "hello"})
        assert answer.status_code == 200, (user, answer.text)
    assert kb.exist(["person_new rdf:type Human"])
