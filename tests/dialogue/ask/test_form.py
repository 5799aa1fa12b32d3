"""The ask role's configuration: fields by JSON-schema type, entity fields, and clear refusals."""

from __future__ import annotations

import json

import pytest

from dialogue.ask.form import AskError, FormState, parse_configuration
from dialogue.ask.progress import opening_state


def config(**properties: object) -> str:
    return json.dumps({"question": "Tell me?", "result_schema_properties": properties})


def test_each_kind_of_field_is_read_from_its_schema() -> None:
    form = parse_configuration(config(
        ok={"type": "boolean"}, age={"type": "integer", "minimum": 0}, height={"type": "number"},
        colour={"enum": ["red", "blue"]}, name={"type": "string"},
        cup={"type": "string", "x-kb-class": "dbr:Cup"}, friend={"type": "string", "format": "kb-person"},
        room={"type": "string", "format": "kb-place"}))
    kinds = {f.name: f.kind for f in form.fields}
    assert kinds == {"ok": "boolean", "age": "integer", "height": "number", "colour": "enum", "name": "string",
                     "cup": "entity", "friend": "entity", "room": "entity"}
    assert form.field("cup").kb_class == "dbr:Cup"
    assert form.field("friend").kinds == {"person"} and form.field("room").kinds == {"zone", "thing"}
    assert form.required == form.names  # every field by default


def test_values_are_checked_by_the_field_schema() -> None:
    form = parse_configuration(config(age={"type": "integer", "minimum": 0, "maximum": 130},
                                      code={"type": "string", "pattern": "^[A-Z]{3}$"}))
    assert form.field("age").check(34) == (34, None)
    value, problem = form.field("age").check(200)
    assert value is None and problem is not None and "130" in problem
    assert form.field("code").check("ABC") == ("ABC", None)
    assert form.field("code").check("abc")[1] is not None


def test_required_and_field_words() -> None:
    form = parse_configuration(json.dumps({"question": "?", "required": ["favourite_colour"],
                                           "result_schema_properties": {"favourite_colour": {"type": "string"},
                                                                        "petName": {"type": "string", "title": "Pet"}}}))
    assert form.required == ("favourite_colour",)
    assert form.field("favourite_colour").words == "favourite colour" and form.field("petName").words == "pet"


def test_the_forms_own_question_asks_for_every_field() -> None:
    properties = {"age": {"type": "integer"}, "tea": {"type": "boolean"},
                  "pet": {"type": "string", "description": "What is your pet called?"}}
    form = parse_configuration(json.dumps({"question": "Age, tea and pet?", "result_schema_properties": properties}))
    assert form.own_question_for("age")  # the first field is asked by the form's question
    assert not form.own_question_for("tea")  # "And tea: yes or no?"
    assert not form.own_question_for("pet")  # its own question
    single = parse_configuration(json.dumps({"question": "Tea?", "required": ["tea"],
                                             "result_schema_properties": properties}))
    assert single.own_question_for("tea")


@pytest.mark.parametrize(("configuration", "message"), [
    ("not json", "not JSON"),
    ('["a"]', "must be a JSON object"),
    ('{"result_schema_properties": {"a": {"type": "integer"}}}', "needs a question"),
    ('{"question": "  ", "result_schema_properties": {"a": {"type": "integer"}}}', "needs a question"),
    ('{"question": "?"}', "needs result_schema_properties"),
    ('{"question": "?", "result_schema_properties": {}}', "needs result_schema_properties"),
    ('{"question": "?", "result_schema_properties": {"a": 3}}', "field 'a': its schema must be a JSON object"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "array"}}}', "type 'array' is not supported"),
    ('{"question": "?", "result_schema_properties": {"a": {"enum": []}}}', "enum must be a non-empty list"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "integer", "x-kb-class": "dbr:Cup"}}}',
     "an entity of the KB is a string"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "string", "format": "kb-car"}}}',
     "format 'kb-car' is not one of"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "integer", "minimum": "low"}}}',
     "minimum must be a number, not 'low'"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "integer", "minimum": "5", "maximum": 3}}}',
     "minimum must be a number"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "integer", "maximum": true}}}',
     "maximum must be a number"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "string", "pattern": "("}}}',
     "its constraints cannot be checked"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "string"}}, "required": ["b"]}',
     "required must list field names"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "string"}}, "prompt": "x"}', "unknown keys"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": ["integer", "string"]}}}',
     "type \\['integer', 'string'\\] is not supported"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": [[]]}}}', "is not supported"),
    ('{"question": "?", "result_schema_properties": {"a": {"enum": [true, false]}}}',
     "a yes/no field is type boolean"),
    ('{"question": "?", "result_schema_properties": {"a": {"type": "integer", "minimum": 10, "maximum": 5}}}',
     "no value is at least 10 and at most 5"),
])
def test_bad_configurations_are_refused_saying_why(configuration: str, message: str) -> None:
    with pytest.raises(AskError, match=message):
        parse_configuration(configuration)


def test_state_round_trips_and_results_omit_what_was_not_obtained() -> None:
    state = FormState(values={"age": 34}, asked="name", given_up=["pets"], tries={"name": 1})
    assert FormState.from_json(state.to_json()) == state
    assert json.loads(state.results()) == {"age": 34}
    assert FormState.from_json("") == FormState()


def test_a_nullable_type_is_its_type() -> None:
    """`{"type": ["integer", "null"]}` (how many generators write an optional field) is an integer field."""
    form = parse_configuration(config(age={"type": ["integer", "null"], "minimum": 0}, ok={"type": ["null", "boolean"]}))
    assert [(f.name, f.kind) for f in form.fields] == [("age", "integer"), ("ok", "boolean")]
    assert form.field("age").check(34) == (34, None) and form.field("age").check(-1)[1] is not None


def test_no_required_field_asks_once() -> None:
    """`"required": []`: the question is asked and the first answer ends the form with what it gave."""
    form = parse_configuration(json.dumps({"question": "Anything?", "required": [],
                                           "result_schema_properties": {"age": {"type": "integer"}}}))
    assert form.required == () and opening_state(form).asked == "age"



@pytest.mark.parametrize(("configuration", "message"), [
    (config(a={"type": "integer", "minimum": 1}).replace(": 1}", ": " + "9" * 5000 + "}"), "5000 digits"),
    (config(a={"type": "string"}).replace('"string"}', '"string", "x": ' + "[" * 10_000 + "]" * 10_000 + "}"),
     "nested more than 32 levels"),
    ('{"question": "?", "result_schema_properties": {"a\\udc00ge": {"type": "integer"}}}', "lone surrogate U\\+DC00"),
])
def test_json_no_field_needs_is_refused_as_a_bad_configuration(configuration: str, message: str) -> None:
    """Once a ValueError, a RecursionError and a 500 at every answer naming the field (dialogue.ask.jsontext)."""
    with pytest.raises(AskError, match=message):
        parse_configuration(configuration)
