"""chatbot_msgs 4.0 stateless turns over HTTP beside the 3.0 incremental shape (issue 16)."""

from __future__ import annotations

import json
from collections.abc import Callable

import httpx

from api.settings import IntentSettings, Settings
from dialogue.llm.testing import ScriptedModel
from tests.api.conftest import SCENE, Live, scene_settings
from tests.api.test_intents import sse
from tests.api.test_webhooks import Receiver
from tests.waiting import until

ASK = {"name": "__ask__", "configuration": json.dumps({
    "question": "How old are you?", "result_schema_properties": {"age": {"type": "integer", "minimum": 0}}})}


def test_a_4_0_turn_needs_no_session_and_stores_nothing(live: Live) -> None:
    history = [{"speaker": "__system__", "text": "Alice just came in."},
               {"speaker": "__assistant__", "text": "Hello Alice!"},
               {"speaker": "person_alice", "text": "pick up the cup"}]
    reply = live.client.post("/dialogues/3f2a-dm-owned/interactions",
                             json={"role": {"name": "__default__", "configuration": "{}"}, "history": history})
    assert reply.status_code == 200, reply.text
    body = reply.json()
    assert set(body) == {"response", "intents", "error_msg", "dialogue_terminal", "results"}
    assert body["intents"][0]["data"] == {"object": "cup_1"} and body["intents"][0]["source"] == "person_alice"
    assert (body["dialogue_terminal"], body["results"]) == (False, "{}")
    assert "3f2a-dm-owned" not in live.services.dialogues.ids()
    # The turn's trace says what the response said (it had null for both).
    (trace,) = live.client.get("/dialogues/3f2a-dm-owned/turns").json()["turns"]
    assert (trace["shape"], trace["dialogue_terminal"], trace["results"]) == ("4.0", False, "{}")
    # The 3.0 shape keeps working, with its three keys.
    old = live.client.post("/dialogues/default/interactions", json={"user_id": "person_alice", "input": "hi"})
    assert set(old.json()) == {"response", "intents", "error_msg"}


def test_a_4_0_ask_turn_reads_the_form_from_the_history(live: Live) -> None:
    history = [{"speaker": "__assistant__", "text": "How old are you?"},
               {"speaker": "person_alice", "text": "hmm, let me think"},
               {"speaker": "__assistant__", "text": "Sorry, I did not get that. How old are you?"},
               {"speaker": "person_alice", "text": "thirty"}]
    body = live.client.post("/dialogues/any-id/interactions", json={"role": ASK, "history": history}).json()
    assert body["dialogue_terminal"] is True and json.loads(body["results"]) == {"age": 30}
    # With an input beside the history, the input is the turn.
    body = live.client.post("/dialogues/any-id/interactions", json={
        "role": ASK, "history": history[:1], "user_id": "person_alice", "input": "no idea"}).json()
    assert body["dialogue_terminal"] is True and json.loads(body["results"]) == {}


def test_the_4_0_history_and_summary_reach_the_model(live_factory: Callable[..., Live]) -> None:
    model = ScriptedModel([{"verbal_ack": "Nice to see you again.", "user_intent": None}])
    live = live_factory(Settings(scene=SCENE), model=model)
    history = [{"speaker": "__system__", "text": "Battery at 80%."},
               {"speaker": "__assistant__", "text": "Hello!"},
               {"speaker": "person_alice", "text": "Do you remember me?"}]
    body = live.client.post("/dialogues/x/interactions", json={
        "role": {"name": "__default__"}, "history": history, "summary": "Alice likes tea."}).json()
    assert body["response"] == "Nice to see you again."
    roles = [(m.role, m.content) for m in model.requests[0].messages]
    assert roles[1] == ("system", "Summary of earlier conversations: Alice likes tea.")
    assert roles[2:4] == [("system", "Battery at 80%."), ("assistant", "Hello!")]
    assert roles[-1][0] == "user" and 'They say: "Do you remember me?"' in roles[-1][1]


def test_bad_4_0_requests(live: Live) -> None:
    client = live.client
    cases = [
        ({"role": {"name": "__default__"}}, 422, "input is required"),
        ({"role": {"name": "__default__"}, "history": [{"speaker": "__assistant__", "text": "Hi"}]}, 422,
         "nothing to answer"),
        ({"input": "hi"}, 422, "user_id is required"),
        ({"role": {"name": "__nope__"}, "history": [{"speaker": "a", "text": "hi"}]}, 400,
         "unsupported dialogue role"),
        ({"role": {"name": "__ask__", "configuration": "{}"}, "history": [{"speaker": "a", "text": "hi"}]}, 400,
         "needs a question"),
        # Bad input, not an unknown dialogue (both were 404 unknown_dialogue).
        ({"role": {"name": "__default__"}, "history": [{"speaker": "", "text": "hi"}]}, 422,
         "body.history.0.speaker"),
        ({"role": {"name": "__default__"}, "summary": "tea \ud800", "history": [{"speaker": "a", "text": "hi"}]},
         400, "not valid Unicode"),
    ]
    for body, status, message in cases:
        refused = client.post("/dialogues/x/interactions", content=json.dumps(body),  # \ud800 escaped
                              headers={"Content-Type": "application/json"})
        assert refused.status_code == status and message in refused.json()["message"], (body, refused.text)


def test_a_4_0_turn_notifies_like_any_turn(live_factory: Callable[..., Live]) -> None:
    """Issue 30, class 9: a stateless turn's intents reach the stream and the webhooks, and its
    speaker's memory (last spoke, summary) is updated, as an incremental turn's are (the ROS node's
    `/intents`: tests/api/ros/test_intents.py)."""
    receiver = Receiver()
    receiver.failing = False
    try:
        live = live_factory(scene_settings(intents=IntentSettings(webhooks=[receiver.url])))
        before = live.client.get("/people/person_tom/memory").json()
        assert (before["last_spoke"], before["summary"]) == (None, "")
        n = live.services.bus.first - 1
        with httpx.Client(base_url=live.url, timeout=60) as client, \
                client.stream("GET", "/intents/stream", params={"after": n}) as stream:
            events = sse(stream.iter_lines())
            assert next(events)[0] == "hello"
            reply = live.client.post("/dialogues/dm-owned/interactions", json={
                "role": {"name": "__default__"}, "history": [
                    {"speaker": "__assistant__", "text": "Hello Tom!"},
                    {"speaker": "person_tom", "text": "please bring me the cup"}]}).json()
            assert reply["intents"][0]["intent"] == "__intent_bring_object__"
            name, ident, pushed = next(events)
        assert (name, ident, pushed["seq"], pushed["dialogue_id"]) == ("intent", str(n + 1), n + 1, "dm-owned")
        assert pushed["intent"] == reply["intents"][0] and pushed["response"] == reply["response"]
        until(lambda: len(receiver.accepted) == 1)
        assert receiver.accepted[0]["intent"] == reply["intents"][0] and receiver.accepted[0]["seq"] == n + 1
        until(lambda: live.client.get("/people/person_tom/memory").json()["last_spoke"] is not None)
        summary = live.client.get("/people/person_tom/memory").json()["summary"]
        assert summary.endswith('asked "please bring me the cup"')
        assert "dm-owned" not in live.services.dialogues.ids()  # still stateless: nothing stored
    finally:
        receiver.close()
