import json
from typing import Any

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


def intents_of(schema: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """The schema's intent objects by the short type name each writes."""
    variants = schema["properties"]["user_intent"]["anyOf"]
    return {v["properties"]["type"]["const"]: v for v in variants if v.get("type") == "object"}


def test_turn_schema_has_closed_enums_of_candidate_ids() -> None:
    schema = turn_schema(SchemaCandidates(["cup_1"], ["person_a", "cup_1"], []))
    intents = intents_of(schema)
    assert "grab_object" in intents and "raw_user_input" not in intents
    bring = intents["bring_object"]["properties"]
    assert bring["object"] == {"enum": ["cup_1", None]}
    assert bring["recipient"] == {"enum": ["person_a", "cup_1", None]}
    assert intents["move_to"]["properties"]["goal"] == {"type": "null"}
    assert schema["required"] == ["verbal_ack", "user_intent", "facts"]


def test_each_intent_has_only_its_own_keys_all_required_type_first() -> None:
    intents = intents_of(turn_schema(SchemaCandidates(["cup_1"], ["p"], ["kitchen"])))
    keys = {name: list(v["properties"]) for name, v in intents.items()}
    assert keys["grab_object"] == ["type", "object"]
    assert keys["bring_object"] == ["type", "object", "recipient"]
    assert keys["place_object"] == ["type", "object", "recipient"]
    assert keys["guide"] == ["type", "recipient", "goal"]
    assert keys["say"] == ["type", "input", "recipient"]
    assert keys["wakeup"] == ["type"]
    assert all(v["required"] == list(v["properties"]) for v in intents.values())


def test_no_key_of_the_answer_is_optional() -> None:
    """A grammar made from the schema ends the answer after its last key: nothing optional to go on with."""
    def optional(node: Any) -> list[str]:
        if isinstance(node, list):
            return [key for item in node for key in optional(item)]
        if not isinstance(node, dict):
            return []
        found = sorted(set(node.get("properties", {})) - set(node.get("required", [])))
        return found + [key for value in node.values() for key in optional(value)]

    assert optional(turn_schema(SchemaCandidates(["cup_1"], ["p"], ["kitchen", "cup_1", "p"]))) == []


def test_short_type_names_are_read_as_the_catalogues() -> None:
    answer = parse_answer('{"verbal_ack": "Hi!", "user_intent": {"type": "greet", "recipient": "p"}, "facts": null}')
    assert answer.user_intent is not None and answer.user_intent.type == "__intent_greet__"
    full = parse_answer('{"user_intent": {"type": "__intent_greet__", "recipient": "p"}}')
    assert full.user_intent is not None and full.user_intent.type == "__intent_greet__"
    unknown = parse_answer('{"user_intent": {"type": "dance"}}')  # left for the validation to refuse
    assert unknown.user_intent is not None and unknown.user_intent.type == "dance"


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


def test_an_ordered_list_of_intents_is_bounded() -> None:
    schema = turn_schema(SchemaCandidates(["cup_1"], ["p"], ["kitchen"]))
    many = next(v for v in schema["properties"]["user_intent"]["anyOf"] if v.get("type") == "array")
    assert (many["minItems"], many["maxItems"]) == (2, MAX_INTENTS)
    assert many["items"]["anyOf"] == [v for v in schema["properties"]["user_intent"]["anyOf"]
                                      if v.get("type") == "object"]
    listed = '{"verbal_ack": "ok", "user_intent": [{"type": "a"}, {"type": "b"}], "facts": null}'
    assert [w.type for w in parse_answer(listed).wishes()] == ["a", "b"]
    two = '{"verbal_ack": "ok", "user_intent": null, "user_intents": [{"type": "a"}, {"type": "b"}]}'
    assert [w.type for w in parse_answer(two).wishes()] == ["a", "b"]
    assert [w.type for w in ChatbotResponse.model_validate({"user_intent": {"type": "a"}}).wishes()] == ["a"]
    too_many = {"user_intents": [{"type": "a"}] * (MAX_INTENTS + 1)}
    with pytest.raises(AnswerError, match="user_intents"):
        parse_answer(json.dumps(too_many))
    with pytest.raises(AnswerError, match="user_intents"):
        parse_answer(json.dumps({"user_intent": [{"type": "a"}] * (MAX_INTENTS + 1)}))


def test_turn_schema_offers_facts_with_closed_predicates_and_id_enums() -> None:
    schema = turn_schema(SchemaCandidates(["cup_1"], ["p"], ["kitchen", "cup_1", "p"]))
    assert "facts" in schema["required"] and {"type": "null"} in schema["properties"]["facts"]["anyOf"]
    facts = schema["properties"]["facts"]["anyOf"][1]
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
