"""/chatbot/dialogue_interaction on a real graph: a turn answers with hri_actions_msgs intents; the
entries chatbot_msgs defines (response_expected false, __system__, __assistant__, an empty input)
mean what they say; refused requests say why and record nothing; the turn deadline is below a
dialogue manager's 5 s, polite fallback included."""

from __future__ import annotations

import json
import time
import uuid
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

from api.settings import Settings
from dialogue.engine import sorry
from tests.api.ros.conftest import Probe, RosNode

SORRY = sorry()  # what the engine says when no answer comes in time

INTERACTION = "/chatbot/dialogue_interaction"
DI = "chatbot_msgs/srv/DialogueInteraction"
NIL = {"uuid": [0] * 16}  # the service's `default` dialogue


def say(probe: Probe, user: str, text: str, dialogue: dict[str, Any] = NIL, **more: Any) -> dict[str, Any]:
    return probe.call(INTERACTION, DI, dialogue_id=dialogue, user_id=user, input=text, **more)


def test_a_turn_answers_with_its_intents_and_rest_sees_the_same_dialogue(ros_node: RosNode, probe: Probe) -> None:
    answer = say(probe, "person_alice", "pick up the cup", response_expected=True)
    assert answer["response"] == "OK, I will pick up the cup." and answer["error_msg"] == ""
    [intent] = answer["intents"]
    assert intent["intent"] == "__intent_grab_object__" and json.loads(intent["data"]) == {"object": "cup_1"}
    assert (intent["source"], intent["modality"], intent["priority"]) == ("person_alice", "__modality_speech__", 128)
    assert 0 < intent["confidence"] <= 1
    turns = ros_node.http.get("/dialogues/default/turns").json()["turns"]
    assert turns[0]["input"] == "pick up the cup" and turns[0]["speaker"] == "person_alice"


def test_entries_recorded_only_are_history_and_nothing_is_misunderstood(ros_node: RosNode, probe: Probe) -> None:
    recorded = say(probe, "__assistant__", "The cookbook is on the table.", response_expected=False)
    assert (recorded["response"], recorded["intents"], recorded["error_msg"]) == ("", [], "")
    # What was only recorded is the history the next turn reads: "it" is the cookbook.
    it = say(probe, "person_alice", "pick it up", response_expected=True)
    assert json.loads(it["intents"][0]["data"]) == {"object": "book_1"}
    # A system update and the robot's own words are never a misunderstood person, even when a
    # response is expected; a person's empty input is legal and gets no answer.
    for user, text in (("__system__", '{"intent": "__intent_greet__", "data": {"recipient": "person_alice"}}'),
                       ("__assistant__", "I will take the cup."), ("__system__", ""), ("person_alice", "")):
        answer = say(probe, user, text, response_expected=True)
        assert (answer["response"], answer["intents"], answer["error_msg"]) == ("", [], ""), (user, text)
    assert say(probe, "person_alice", "pick it up", response_expected=True)["intents"][0]["data"] == \
        '{"object": "cup_1"}'


def test_refused_requests_say_why_and_record_nothing(ros_node: RosNode, probe: Probe) -> None:
    unknown = {"uuid": list(uuid.uuid4().bytes)}
    refused = say(probe, "person_alice", "pick up the cup", unknown, response_expected=True)
    assert refused["response"] == "" and refused["intents"] == []
    assert "unknown dialogue" in refused["error_msg"] and "/chatbot/start_dialogue" in refused["error_msg"]
    limit = Settings().limits.max_input_chars
    huge = say(probe, "person_alice", "pick up the cup " + "x" * limit, response_expected=True)
    assert huge["intents"] == [] and f"the limit is {limit}" in huge["error_msg"]
    bad_locale = say(probe, "person_alice", "pick up the cup", response_expected=True, locale="klingon please")
    assert bad_locale["intents"] == [] and "not a language tag" in bad_locale["error_msg"]
    nobody = say(probe, "", "pick up the cup", response_expected=True)
    assert nobody["intents"] == [] and "user_id is required" in nobody["error_msg"]
    assert ros_node.http.get("/dialogues/default/turns").json()["turns"] == []  # none of them was a turn


def test_a_model_that_never_answers_gets_the_polite_fallback_before_a_5_s_caller_gives_up(
        ros_node_factory: Callable[..., RosNode], probe: Probe, silent_model: str) -> None:
    ros_node_factory("--scene", "none", "--llm", silent_model)
    # dialogue_manager waits 5 s (chatbot_response_timeout): the probe gives up then too.
    answer = probe.call(INTERACTION, DI, timeout=5.0, dialogue_id=NIL, user_id="person_alice",
                        input="glorp the frobnicator", response_expected=True)
    assert answer["response"] == SORRY and answer["error_msg"]
    assert [i["intent"] for i in answer["intents"]] == ["__raw_user_input__"]
    assert json.loads(answer["intents"][0]["data"]) == {"input": "glorp the frobnicator"}


def test_a_turn_awaited_holds_up_neither_the_chatbot_nor_the_kb(
        ros_node_factory: Callable[..., RosNode], probe: Probe, silent_model: str, ros_env: dict[str, str],
        tmp_path: Path) -> None:
    ros_node_factory("--scene", "none", "--llm", silent_model)
    other = Probe(ros_env, tmp_path / "other.log")
    calls = {"/chatbot/get_supported_locales": ("i18n_msgs/srv/GetLocales", {}),
             "/kb/query": ("kb_msgs/srv/Query", {"patterns": ["?s rdf:type owl:Class"]})}
    try:
        # Every client has found its service first (only recorded: the model is not asked).
        say(probe, "__assistant__", "Hello.", response_expected=False)
        for service, (kind, request) in calls.items():
            other.call(service, kind, **request)
        with ThreadPoolExecutor(1) as pool:
            # The model never answers: this turn is awaited until the turn's deadline (4 s).
            turn = pool.submit(say, probe, "person_alice", "glorp the frobnicator", response_expected=True)
            time.sleep(1.0)  # the turn is being awaited by now
            answers = [other.call(service, kind, **request) for service, (kind, request) in calls.items()]
            assert not turn.done()  # both were answered while the turn was still being awaited
            assert answers[0]["locales"] == [] and answers[1]["success"] is True
            assert turn.result(30)["response"] == SORRY
    finally:
        other.close()
