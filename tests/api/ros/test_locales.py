"""i18n_msgs on the chatbot, on a real graph: the supported locales, and the default locale set by the
SetLocale action (feedback, then the result), refused with the reason when the service cannot take it."""

from __future__ import annotations

import json
import uuid
from typing import Any

from tests.api.ros.conftest import Probe, RosNode

SET = "/chatbot/set_default_locale"


def default_locale(probe: Probe) -> str:
    answer = probe.call("/chatbot/get_parameters", "rcl_interfaces/srv/GetParameters", names=["default_locale"])
    value: str = answer["values"][0]["string_value"]
    return value


def set_locale(probe: Probe, locale: str) -> dict[str, Any]:
    goal = probe("goal", action=SET, type="i18n_msgs/action/SetLocale", goal={"locale": locale})
    return probe("result", goal=goal["goal"])


def test_locales_supported_and_the_default_one_set(ros_node: RosNode, probe: Probe) -> None:
    supported = probe.call("/chatbot/get_supported_locales", "i18n_msgs/srv/GetLocales")
    assert supported["locales"] == ros_node.http.get("/locales").json()["locales"] == ["en_GB", "en_US"]
    done = set_locale(probe, "en-us")
    assert done["status"] == "succeeded" and done["result"]["error_msg"] == ""
    assert [json.loads(f["progress"]) for f in done["feedback"]] == [{"chatbot": "complete"}]
    assert default_locale(probe) == "en_US"
    # A dialogue started without a locale has the default one.
    goal = probe("goal", action="/chatbot/start_dialogue", type="chatbot_msgs/action/Dialogue",
                 goal={"role": {"name": "__default__"}})
    dialogue_id = str(uuid.UUID(goal["goal"]))
    ros_node.http.post(f"/dialogues/{dialogue_id}/interactions", json={"user_id": "person_alice", "input": "hi"})
    assert ros_node.http.get(f"/dialogues/{dialogue_id}/turns").json()["turns"][0]["locale"] == "en_US"


def test_a_locale_the_service_cannot_take_is_refused_and_nothing_changes(ros_node: RosNode, probe: Probe) -> None:
    for locale, why in (("fr_FR", "English only"), ("klingon please", "not a language tag")):
        refused = set_locale(probe, locale)
        assert refused["status"] == "aborted" and why in refused["result"]["error_msg"]
    assert default_locale(probe) == ""
    # Parameters read at start are not changed behind the node's back; the default locale is checked.
    changes = probe.call("/chatbot/set_parameters", "rcl_interfaces/srv/SetParameters", parameters=[
        {"name": "turn_deadline", "value": {"type": 3, "double_value": 9.0}},
        {"name": "default_locale", "value": {"type": 4, "string_value": "nonsense words"}}])["results"]
    assert [c["successful"] for c in changes] == [False, False]
    assert "read-only" in changes[0]["reason"]
    assert "not a language tag" in changes[1]["reason"]
    assert default_locale(probe) == ""
