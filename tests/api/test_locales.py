"""GET /locales and per-dialogue / per-turn locales over HTTP (issue 16)."""

from __future__ import annotations

from collections.abc import Callable

from api.settings import Settings
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.testing import ScriptedModel
from tests.api.conftest import SCENE, Live


def test_locales_of_the_rules_and_of_a_model(live_factory: Callable[..., Live]) -> None:
    rules = live_factory()
    assert rules.client.get("/locales").json() == {"locales": ["en_GB", "en_US"], "rules": ["en"]}
    model = live_factory(Settings(scene=SCENE), model=HybridModel(ScriptedModel()))
    assert model.client.get("/locales").json() == {"locales": [], "rules": ["en"]}  # empty: any locale


def test_a_french_turn_is_handed_over_not_misparsed(live: Live) -> None:
    dialogue_id = live.client.post("/dialogues", json={"locale": "fr_FR"}).json()["dialogue_id"]
    body = live.client.post(f"/dialogues/{dialogue_id}/interactions",
                            json={"user_id": "person_alice", "input": "pick up the cup"}).json()
    assert body["response"] == "" and "English only" in body["error_msg"]
    assert body["intents"] == [{"intent": "__raw_user_input__", "data": {"input": "pick up the cup", "locale": "fr_FR"},
                                "source": "person_alice", "modality": "__modality_speech__", "priority": 128,
                                "confidence": 1.0}]
    # The turn's locale overrides the dialogue's.
    english = live.client.post(f"/dialogues/{dialogue_id}/interactions",
                               json={"user_id": "person_alice", "input": "pick up the cup", "locale": "en_GB"}).json()
    assert english["intents"][0]["intent"] == "__intent_grab_object__"


def test_bad_locales_are_refused(live: Live) -> None:
    for call in (lambda: live.client.post("/dialogues", json={"locale": "klingon"}),
                 lambda: live.client.post("/dialogues/default/interactions",
                                          json={"user_id": "a", "input": "hi", "locale": "xx_YY"})):
        refused = call()
        assert refused.status_code == 422 and "e.g. en_GB or fr_FR" in refused.json()["message"]


def test_an_empty_locale_is_no_locale(live: Live) -> None:
    """chatbot_msgs' locale is optional and a ROS message's unset string is "": a bridge that copies
    the fields sends it. It means no locale (it was refused with 422)."""
    started = live.client.post("/dialogues", json={"locale": ""})
    assert started.status_code == 201, started.text
    body = live.client.post(f"/dialogues/{started.json()['dialogue_id']}/interactions",
                            json={"user_id": "person_alice", "input": "pick up the cup", "locale": ""}).json()
    assert body["intents"][0]["intent"] == "__intent_grab_object__"
