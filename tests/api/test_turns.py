"""GET /dialogues/{id}/turns: every turn's trace, most recent first, bounded, without the token."""

from __future__ import annotations

from collections.abc import Callable

from api.settings import Settings
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.testing import ScriptedModel
from tests.api.conftest import SCENE, Live

TOKEN = "trace-secret-42"
AUTH = {"Authorization": f"Bearer {TOKEN}"}


def test_the_trace_of_rules_model_and_repair_turns(live_factory: Callable[..., Live]) -> None:
    grab = {"verbal_ack": "Taking it.", "user_intent": {"type": "__intent_grab_object__", "object": "cup_1",
                                                        "recipient": None, "goal": None, "input": None}}
    model = ScriptedModel(["{oops", grab])
    live = live_factory(Settings(scene=SCENE, token=TOKEN), model=HybridModel(model))
    client = live.client
    client.post("/dialogues/default/interactions", headers=AUTH,
                json={"user_id": "person_alice", "input": "pick up the cup"}).raise_for_status()
    client.post("/dialogues/default/interactions", headers=AUTH,
                json={"user_id": "person_alice", "input": f"zorglub {TOKEN} frobnicate"})
    body = client.get("/dialogues/default/turns", headers=AUTH).json()
    assert body["dialogue_id"] == "default"
    latest, first = body["turns"]
    assert TOKEN not in str(body)
    assert first["answered_by"] == "rules" and first["exchanges"] == [] and first["input"] == "pick up the cup"
    assert first["intents"][0]["data"] == {"object": "cup_1"}
    # the rules answered: no prompt was built, so none of its entities are listed
    assert first["snapshot"]["entities"] > 0 and first["snapshot"]["by_kind"] == {} and not first["snapshot"]["focus"]
    assert latest["snapshot"]["by_kind"]["person"] == 2 and "person_alice" in latest["snapshot"]["focus"]
    assert latest["answered_by"] == "model" and latest["backend"] == "scripted" and latest["repaired"] is True
    bad, repair = latest["exchanges"]
    assert bad["raw_answer"] == "{oops" and "not valid JSON" in bad["error"]
    assert bad["messages"][0]["role"] == "system" and "[redacted]" in bad["messages"][-1]["content"]
    assert bad["schema"]["properties"]["user_intent"] and repair["repair"] is True
    assert latest["validation_errors"] == [bad["error"]]
    assert [s["name"] for s in latest["stages"]][-1] == "total"
    assert {"ground", "rules", "model", "validate"} <= {s["name"] for s in latest["stages"]}
    assert len(client.get("/dialogues/default/turns?limit=1", headers=AUTH).json()["turns"]) == 1


def test_unknown_dialogues_and_empty_ones(live: Live) -> None:
    missing = live.client.get("/dialogues/nope/turns")
    assert (missing.status_code, missing.json()["code"]) == (404, "unknown_dialogue")
    started = live.client.post("/dialogues", json={}).json()["dialogue_id"]
    assert live.client.get(f"/dialogues/{started}/turns").json()["turns"] == []
    assert live.client.get("/dialogues/default/turns?limit=0").status_code == 422
    live.client.delete("/dialogues/default")


def test_stateless_turns_are_traced_under_their_id(live: Live) -> None:
    live.client.post("/dialogues/dm-7/interactions", json={
        "role": {"name": "__default__"}, "history": [{"speaker": "person_alice", "text": "hello"}]})
    (trace,) = live.client.get("/dialogues/dm-7/turns").json()["turns"]
    assert trace["shape"] == "4.0" and trace["dialogue_id"] == "dm-7"
