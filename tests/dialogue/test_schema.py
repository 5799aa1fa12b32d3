import json

import pytest

from dialogue.schema import (
    MAX_FACTS,
    MAX_INTENTS,
    AnswerError,
    ChatbotResponse,
    SchemaCandidates,
    extract_json,
    parse_answer,
    turn_schema,
)


def test_turn_schema_has_closed_enums_of_candidate_ids() -> None:
    schema = turn_schema(SchemaCandidates(["cup_1"], ["person_a", "cup_1"], []))
    user_intent = schema["properties"]["user_intent"]["anyOf"][0]["properties"]
    assert "__intent_grab_object__" in user_intent["type"]["enum"]
    assert "__raw_user_input__" not in user_intent["type"]["enum"]
    assert user_intent["object"] == {"enum": ["cup_1", None]}
    assert user_intent["recipient"] == {"enum": ["person_a", "cup_1", None]}
    assert user_intent["goal"] == {"type": "null"}
    assert schema["required"] == ["verbal_ack", "user_intent"]


def test_json_is_extracted_string_aware_from_prose() -> None:
    content = 'Sure! {"verbal_ack": "it is 10:30, see http://x.org {ok}", "user_intent": null} trailing }'
    assert extract_json(content)["verbal_ack"] == "it is 10:30, see http://x.org {ok}"


def test_parse_answer_validates_and_tolerates_missing_keys() -> None:
    answer = parse_answer('{"user_intent": {"type": "__intent_greet__", "recipient": "p"}}')
    assert answer.verbal_ack is None
    assert answer.user_intent is not None and answer.user_intent.recipient == "p"


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("no json here", "no JSON object"),
        ('{"verbal_ack": "x",', "not valid JSON"),
        ('{"verbal_ack": 3, "user_intent": "grab"}', "does not match the schema"),
    ],
)
def test_bad_answers_raise_answer_error_with_reason(content: str, message: str) -> None:
    with pytest.raises(AnswerError, match=message):
        parse_answer(content)


def test_non_object_json_is_an_answer_error() -> None:
    with pytest.raises(AnswerError):
        parse_answer("[1, 2] {3}")


def test_an_ordered_list_of_intents_is_optional_and_bounded() -> None:
    schema = turn_schema(SchemaCandidates(["cup_1"], ["p"], ["kitchen"]))
    assert "user_intents" in schema["properties"] and "user_intents" not in schema["required"]
    many = schema["properties"]["user_intents"]["anyOf"][0]
    assert many["maxItems"] == MAX_INTENTS and many["items"] == schema["properties"]["user_intent"]["anyOf"][0]
    two = '{"verbal_ack": "ok", "user_intent": null, "user_intents": [{"type": "a"}, {"type": "b"}]}'
    assert [w.type for w in parse_answer(two).wishes()] == ["a", "b"]
    assert [w.type for w in ChatbotResponse.model_validate({"user_intent": {"type": "a"}}).wishes()] == ["a"]
    too_many = {"user_intents": [{"type": "a"}] * (MAX_INTENTS + 1)}
    with pytest.raises(AnswerError, match="user_intents"):
        parse_answer(json.dumps(too_many))


def test_turn_schema_offers_facts_with_closed_predicates_and_id_enums() -> None:
    schema = turn_schema(SchemaCandidates(["cup_1"], ["p"], ["kitchen", "cup_1", "p"]))
    assert "facts" in schema["properties"] and "facts" not in schema["required"]
    facts = schema["properties"]["facts"]["anyOf"][0]
    fact = facts["items"]["properties"]
    assert fact["predicate"]["enum"] == ["name", "belongsTo", "isIn", "isOn", "likes", "dislikes"]
    assert fact["subject"]["enum"] == ["kitchen", "cup_1", "p", None]
    # The object is an id of the situation, or words: a name, a kind of thing; null asks.
    assert fact["object"]["anyOf"][0] == {"enum": ["kitchen", "cup_1", "p"]}
    assert {"type": "null"} in fact["object"]["anyOf"]
    assert facts["maxItems"] == MAX_FACTS


def test_an_answer_with_facts_parses() -> None:
    answer = parse_answer('{"verbal_ack": null, "user_intent": null, '
                          '"facts": [{"subject": "p", "predicate": "likes", "object": "tea"}]}')
    assert answer.facts is not None and answer.facts[0].object == "tea" and answer.wishes() == []
