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
