import json

import pytest
from pydantic import ValidationError

from dialogue import intents as I


def test_catalogue_has_every_intent_msg_2_5_constant() -> None:
    expected = {
        "__raw_user_input__",
        "__intent_engage_with__",
        "__intent_move_to__",
        "__intent_guide__",
        "__intent_grab_object__",
        "__intent_bring_object__",
        "__intent_place_object__",
        "__intent_greet__",
        "__intent_say__",
        "__intent_present_content__",
        "__intent_perform_motion__",
        "__intent_start_activity__",
        "__intent_stop_activity__",
        "__intent_wakeup__",
        "__intent_suspend__",
    }
    assert set(I.CATALOGUE) == expected
    assert I.CATALOGUE[I.GUIDE].required == ("goal", "recipient")
    assert I.CATALOGUE[I.PLACE_OBJECT].required == ("recipient",)
    assert I.CATALOGUE[I.PLACE_OBJECT].optional == ("object",)
    assert I.CATALOGUE[I.STOP_ACTIVITY].required == ()
    assert I.RAW_USER_INPUT not in I.EXTRACTABLE


def test_sources_and_modalities_are_the_exact_constants() -> None:
    assert {"__myself__", "__remote_supervisor__", "__unknown_agent__", "__unknown__"} == I.SOURCES
    assert I.MODALITY_SPEECH == "__modality_speech__"
    assert len(I.MODALITIES) == 5


def test_make_intent_sets_defaults_and_drops_null_roles() -> None:
    intent = I.make_intent(
        I.GRAB_OBJECT, {"object": "cup_1", "agent": None}, source="person_a", confidence=0.9
    )
    assert intent.data == {"object": "cup_1"}
    assert intent.priority == 128
    assert intent.modality == I.MODALITY_SPEECH
    assert intent.source == "person_a"
    assert json.loads(intent.data_json()) == {"object": "cup_1"}


def test_missing_required_role_is_refused() -> None:
    with pytest.raises(I.IntentError, match="missing required role"):
        I.make_intent(I.BRING_OBJECT, {"object": "cup_1"}, source="p", confidence=1.0)
    with pytest.raises(I.IntentError, match="missing required role"):
        I.make_intent(I.GREET, {"recipient": "  "}, source="p", confidence=1.0)


def test_unknown_role_or_type_key_is_refused() -> None:
    with pytest.raises(I.IntentError, match="no role 'type'"):
        I.make_intent(I.GREET, {"recipient": "p", "type": I.GREET}, source="p", confidence=1.0)
    with pytest.raises(I.IntentError, match="unknown intent"):
        I.make_intent("__intent_fly__", {}, source="p", confidence=1.0)


def test_confidence_and_modality_are_validated() -> None:
    with pytest.raises(ValidationError):
        I.make_intent(I.WAKEUP, {}, source="p", confidence=1.5)
    with pytest.raises(ValidationError):
        I.Intent(intent=I.WAKEUP, data={}, source="p", modality="speech")


def test_raw_user_input_data_is_serialised_json_with_locale() -> None:
    raw = I.raw_user_input('say "hi" {now}', source="p", locale="en_GB")
    assert raw.intent == I.RAW_USER_INPUT
    assert json.loads(raw.data_json()) == {"input": 'say "hi" {now}', "locale": "en_GB"}
    assert I.raw_user_input("x", source="").source == I.UNKNOWN


def test_roles_that_name_nothing_carry_any_json_value() -> None:
    """A ROS Intent's `data` is any JSON object: `other_data`, the SAY text, an activity's name may
    be numbers, lists, objects; the ROS message's string says them as JSON."""
    other = {"level": 2, "players": ["person_a", "person_b"], "timed": True, "bonus": None, "score": 0.5}
    intent = I.make_intent(I.START_ACTIVITY, {"object": "memory_game", "other_data": other}, source="p",
                           confidence=1.0)
    assert intent.data == {"object": "memory_game", "other_data": other}
    assert json.loads(intent.data_json()) == intent.data
    said = I.make_intent(I.SAY, {"object": {"text": "Hi", "gesture": "wave"}, "recipient": "p"}, source="p",
                         confidence=1.0)
    assert said.data["object"] == {"text": "Hi", "gesture": "wave"}
    for falsy in (0, False, [], {}):  # a value, not an empty role
        assert I.make_intent(I.STOP_ACTIVITY, {"other_data": falsy}, source="p", confidence=1.0).data == {
            "other_data": falsy}
    assert I.Intent.model_validate_json(intent.model_dump_json()) == intent


@pytest.mark.parametrize(("intent", "data", "says"), [
    (I.GREET, {"recipient": 7}, "data.recipient of __intent_greet__ names an entity: a string (a KB id), not 7"),
    (I.BRING_OBJECT, {"object": ["cup_1"], "recipient": "p"}, "data.object of __intent_bring_object__ names an"),
    (I.GRAB_OBJECT, {"object": "cup_1", "agent": {"id": "p"}}, "data.agent of __intent_grab_object__ names an"),
    (I.RAW_USER_INPUT, {"input": 42}, "data.input of __raw_user_input__ is text: a string, not 42"),
    (I.START_ACTIVITY, {"object": "game", "other_data": float("nan")}, "data.other_data: nan is not a finite"),
    (I.START_ACTIVITY, {"object": "game", "other_data": {"x": -float("inf")}}, "-inf is not a finite number"),
    (I.START_ACTIVITY, {"object": "game", "other_data": 10 ** 100}, "data.other_data has a number of 101 digits"),
    pytest.param(I.START_ACTIVITY, {"object": "game", "other_data": [10 ** 5000]},
                 "has a number of more than 100 digits", id="10**5000"),
    (I.START_ACTIVITY, {"object": "game", "other_data": {"k\ud800": 1}}, "text of data.other_data is not valid"),
    (I.SAY, {"object": ["hi\udfff"]}, "lone surrogate U+DFFF"),
])
def test_a_value_the_contract_does_not_allow_is_refused_saying_where(intent: str, data: dict[str, object],
                                                                      says: str) -> None:
    with pytest.raises(I.IntentError) as made:
        I.make_intent(intent, data, source="p", confidence=1.0)  # type: ignore[arg-type]
    assert says in str(made.value)
    with pytest.raises(ValidationError) as built:  # the model holds to it too, whoever builds one
        I.Intent(intent=intent, data=data, source="p")  # type: ignore[arg-type]
    assert says in str(built.value)


def test_nesting_is_bounded_before_anything_walks_it() -> None:
    def nested(levels: int) -> object:
        value: object = 1
        for _ in range(levels):
            value = [value]
        return value

    fine = I.Intent(intent=I.STOP_ACTIVITY, data={"other_data": nested(32)}, source="p")  # type: ignore[dict-item]
    assert json.loads(fine.data_json())["other_data"] == nested(32)
    for levels in (33, 5000):  # 5000: past pydantic's own recursion guard, refused in one line here
        with pytest.raises(ValidationError) as refused:
            I.Intent(intent=I.STOP_ACTIVITY, data={"other_data": nested(levels)}, source="p")  # type: ignore[dict-item]
        assert "data.other_data is nested more than 32 levels deep" in str(refused.value)
        assert len(str(refused.value)) < 400


def test_a_null_role_is_left_out_by_make_intent_and_refused_in_a_whole_intent() -> None:
    assert I.make_intent(I.GREET, {"recipient": "p", "agent": None}, source="p", confidence=1.0).data == {
        "recipient": "p"}
    with pytest.raises(ValidationError) as refused:
        I.Intent(intent=I.GREET, data={"recipient": "p", "agent": None}, source="p")
    assert "data.agent is null; leave a role with no value out" in str(refused.value)
