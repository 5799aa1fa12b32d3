"""The ask role's form: the question and the fields to fill, read from the role's configuration, and
the form's state between turns.

The configuration is chatbot_msgs' ask role (also what `/skill/ask`'s `answers_schema` becomes):
``{"question": "...", "result_schema_properties": {NAME: JSON schema, ...}, "required": [NAME...]}``
(`required` is optional: every field by default). A field's schema has a `type` (`boolean`,
`integer`, `number`, `string`) or an `enum`; `minimum`, `maximum`, `exclusiveMinimum`,
`exclusiveMaximum`, `minLength`, `maxLength`, `pattern`, `title` and `description` are honoured.

**Entities of the KB.** A string field is filled with the id of a KB entity when its schema says
which: ``"format": "kb-person" | "kb-thing" | "kb-place" | "kb-entity"`` (the kind), and/or
``"x-kb-class": "dbr:Cup"`` (instances of that class, its subclasses included). Its value is always
an id of the KB; several candidates get a clarifying question.

>>> form = parse_configuration('{"question": "How old are you?", '
...     '"result_schema_properties": {"age": {"type": "integer", "minimum": 0}}}')
>>> form.question, [(f.name, f.kind) for f in form.fields], form.required
('How old are you?', [('age', 'integer')], ('age',))
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Annotated, Any, Literal

from pydantic import AfterValidator, BaseModel, Field, TypeAdapter, ValidationError
from pydantic_core import PydanticCustomError, SchemaError

from dialogue.ask.jsontext import ConfigurationError, decode
from dialogue.errors import DialogueError
from dialogue.jsonvalues import MAX_DIGITS
from dialogue.reference.resolution import ALL_KINDS, ANYWHERE, PERSON, PLACE, THING
from dialogue.reference.snapshot import Kind

ASK_ROLE = "__ask__"
FieldKind = Literal["boolean", "integer", "number", "string", "enum", "entity"]

#: `format` of an entity field -> the kinds of entity it may name.
ENTITY_FORMATS: dict[str, frozenset[Kind]] = {
    "kb-person": PERSON,
    "kb-thing": THING,
    "kb-place": PLACE,
    "kb-entity": ANYWHERE,
}
_SCALAR_TYPES = {"boolean": "boolean", "integer": "integer", "number": "number", "string": "string"}
_BOUNDS = ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum")
MAX_FIELDS = 16
MAX_QUESTION = 500


class AskError(DialogueError, ValueError):
    """An ask role configuration that cannot be used; the message says what is wrong."""


@dataclass(frozen=True)
class FormField:
    name: str
    kind: FieldKind
    #: The field's JSON schema as configured.
    schema: Mapping[str, Any]
    #: Entity fields: the kinds of entity, and the class its instances belong to (if given).
    kinds: frozenset[Kind] = ALL_KINDS
    kb_class: str | None = None

    @property
    def enum(self) -> tuple[Any, ...]:
        return tuple(self.schema.get("enum", ()))

    @property
    def words(self) -> str:
        """How the field is said: its title, else its name with spaces ("favourite_colour")."""
        title = self.schema.get("title")
        if isinstance(title, str) and title.strip():
            return title.strip().lower()
        return re.sub(r"(?<=[a-z])(?=[A-Z])|[_\-]+", " ", self.name).strip().lower()

    def validator(self) -> TypeAdapter[Any]:
        """Checks a value against the field's schema (the same for the rules' and a model's values)."""
        return TypeAdapter(_python_type(self))

    def check(self, value: Any) -> tuple[Any, str | None]:
        """The value as the field holds it, or the reason it cannot hold it."""
        try:
            return self.validator().validate_python(value), None
        except ValidationError as exc:  # one value: one reason (a number field's int, then float)
            return None, str(exc.errors()[0]["msg"])


def _number(field: FormField) -> Any:
    """A whole number stays an int (exact however long: a float rounds past 2**53), a number field
    takes a float too; both within the bounds every reader of the results takes
    (``jsonvalues``: finite, at most 100 digits)."""
    schema = field.schema

    def bounds(allow_inf_nan: bool | None = None) -> Any:  # pydantic checks an int's finiteness as a float
        return Field(ge=schema.get("minimum"), le=schema.get("maximum"), gt=schema.get("exclusiveMinimum"),
                     lt=schema.get("exclusiveMaximum"), allow_inf_nan=allow_inf_nan)

    whole = Annotated[int, bounds(), AfterValidator(_held)]
    if field.kind == "integer":
        return whole
    return whole | Annotated[float, bounds(allow_inf_nan=False), AfterValidator(_held)]


def _held(value: float) -> float:
    if isinstance(value, int) and abs(value) >= 10**MAX_DIGITS:
        raise PydanticCustomError("too_many_digits", "Input should have at most {digits} digits",
                                  {"digits": MAX_DIGITS})
    return value


def _string(field: FormField) -> Any:
    schema = field.schema
    limits = Field(
        min_length=schema.get("minLength", 1),
        max_length=schema.get("maxLength", 200),
        pattern=schema.get("pattern"),
    )
    return Annotated[str, limits]


#: The Python type that checks a value of each kind of field (an entity: an id, resolved against the KB).
_PYTHON_TYPES: dict[FieldKind, Callable[[FormField], Any]] = {
    "enum": lambda field: Literal[field.enum],
    "boolean": lambda field: bool,
    "integer": _number,
    "number": _number,
    "string": _string,
    "entity": lambda field: str,
}


def _python_type(field: FormField) -> Any:
    return _PYTHON_TYPES[field.kind](field)


@dataclass(frozen=True)
class AskForm:
    question: str
    fields: tuple[FormField, ...]
    required: tuple[str, ...]

    def field(self, name: str) -> FormField:
        return next(f for f in self.fields if f.name == name)

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(f.name for f in self.fields)

    def own_question_for(self, name: str) -> bool:
        """Whether the robot asks for field `name` with the form's own question, which asks for every
        field at once (the first field's, or the one required field's), rather than one of its own
        (a description that is a question)."""
        description = self.field(name).schema.get("description")
        if isinstance(description, str) and description.strip().endswith("?"):
            return False
        return name == self.fields[0].name or len(self.required) == 1


def _field(name: str, schema: Any) -> FormField:
    where = f"field {name!r}"
    if not isinstance(schema, dict):
        raise AskError(f'{where}: its schema must be a JSON object, e.g. {{"type": "integer"}}')
    kind = _type_of(schema)
    if "enum" in schema:
        values = schema["enum"]
        if (
            not isinstance(values, list)
            or not values
            or not all(isinstance(v, str | int | float) for v in values)
        ):
            raise AskError(f"{where}: enum must be a non-empty list of strings or numbers")
        if any(isinstance(v, bool) for v in values):
            raise AskError(f"{where}: enum values are strings or numbers; a yes/no field is type boolean")
        return FormField(name, "enum", schema)
    if not isinstance(kind, str) or kind not in _SCALAR_TYPES:
        raise AskError(
            f"{where}: type {kind!r} is not supported; use boolean, integer, number or string "
            "(an enum, or an entity of the KB with format kb-person/kb-thing/kb-place/kb-entity "
            "or x-kb-class)"
        )
    form, kb_class = schema.get("format"), schema.get("x-kb-class")
    if kb_class is not None and (not isinstance(kb_class, str) or not kb_class.strip()):
        raise AskError(f'{where}: x-kb-class must be a class of the KB, e.g. "dbr:Cup"')
    if isinstance(form, str) and form.startswith("kb-") and form not in ENTITY_FORMATS:
        raise AskError(f"{where}: format {form!r} is not one of {sorted(ENTITY_FORMATS)}")
    if form in ENTITY_FORMATS or kb_class is not None:
        if kind != "string":
            raise AskError(f"{where}: an entity of the KB is a string (its id), not {kind!r}")
        kinds = ENTITY_FORMATS.get(form, ALL_KINDS) if isinstance(form, str) else ALL_KINDS
        return FormField(name, "entity", schema, kinds, kb_class.strip() if kb_class else None)
    for bound in _BOUNDS:
        value = schema.get(bound)
        if value is not None and (not isinstance(value, int | float) or isinstance(value, bool)):
            raise AskError(f"{where}: {bound} must be a number, not {value!r}")
    field = FormField(name, _SCALAR_TYPES[kind], schema)  # type: ignore[arg-type]
    try:
        field.validator()
    except (TypeError, ValueError, SchemaError) as exc:  # a bound of the wrong type, a bad pattern
        raise AskError(f"{where}: its constraints cannot be checked: {exc}") from None
    low, high = schema.get("minimum"), schema.get("maximum")
    if low is not None and high is not None and low > high:  # the field could never be filled
        raise AskError(f"{where}: no value is at least {low} and at most {high}")
    return field


def _type_of(schema: Mapping[str, Any]) -> Any:
    """The field's JSON-schema type; a nullable one (``["integer", "null"]``) is its non-null type."""
    kind = schema.get("type")
    if isinstance(kind, list):
        named = [k for k in kind if k != "null"]
        return named[0] if len(named) == 1 and isinstance(named[0], str) else kind
    return kind


def parse_configuration(configuration: str) -> AskForm:
    """The form of an ask role's configuration, or AskError saying what is wrong with it."""
    try:
        data = decode(configuration or "{}")
    except ConfigurationError as exc:
        raise AskError(str(exc)) from None
    except json.JSONDecodeError as exc:
        raise AskError(f"the ask role's configuration is not JSON: {exc}") from None
    if not isinstance(data, dict):
        raise AskError(
            "the ask role's configuration must be a JSON object with question and result_schema_properties"
        )
    question = data.get("question")
    if not isinstance(question, str) or not question.strip() or len(question) > MAX_QUESTION:
        raise AskError(
            f"the ask role needs a question: a non-empty string of at most {MAX_QUESTION} "
            'characters, e.g. "How old are you?"'
        )
    properties = data.get("result_schema_properties")
    if not isinstance(properties, dict) or not properties:
        raise AskError(
            "the ask role needs result_schema_properties: a JSON object of the fields to fill, "
            'e.g. {"age": {"type": "integer", "minimum": 0}}'
        )
    if len(properties) > MAX_FIELDS:
        raise AskError(f"the ask role takes at most {MAX_FIELDS} fields, not {len(properties)}")
    fields = tuple(_field(name, schema) for name, schema in properties.items())
    if any(not name.strip() for name in properties):
        raise AskError("a field name of the ask role is empty")
    required = data.get("required", list(properties))
    if not isinstance(required, list) or not all(isinstance(r, str) and r in properties for r in required):
        raise AskError(f"required must list field names of result_schema_properties: {sorted(properties)}")
    unknown = set(data) - {"question", "result_schema_properties", "required"}
    if unknown:
        raise AskError(f"unknown keys in the ask role's configuration: {sorted(unknown)}")
    return AskForm(question.strip(), fields, tuple(dict.fromkeys(required)))


#: `--field name:TYPE` types that are not JSON-schema types: entity kinds.
_KIND_WORDS = {
    "person": "kb-person",
    "thing": "kb-thing",
    "object": "kb-thing",
    "place": "kb-place",
    "entity": "kb-entity",
}


def field_schema_of(spec: str) -> tuple[str, dict[str, Any]]:
    """A field from ``name:TYPE`` (the CLI's `--field`): TYPE is boolean, integer, number, string,
    person, thing, place, entity, a KB class (``cup:dbr:Cup``) or values ``colour:red|green|blue``.

    >>> field_schema_of("cup:dbr:Cup"), field_schema_of("size:s|m|l")
    (('cup', {'type': 'string', 'x-kb-class': 'dbr:Cup'}), ('size', {'enum': ['s', 'm', 'l']}))
    """
    name, _, kind = spec.partition(":")
    name, kind = name.strip(), kind.strip()
    if not name or not kind:
        raise AskError(f"field {spec!r}: write name:TYPE, e.g. age:integer, cup:dbr:Cup or size:s|m|l")
    if kind in _SCALAR_TYPES:
        return name, {"type": kind}
    if kind in _KIND_WORDS:
        return name, {"type": "string", "format": _KIND_WORDS[kind]}
    if "|" in kind:
        return name, {"enum": [v.strip() for v in kind.split("|") if v.strip()]}
    if ":" in kind:
        return name, {"type": "string", "x-kb-class": kind}
    raise AskError(
        f"field {spec!r}: unknown type {kind!r}; use boolean, integer, number, string, person, thing, "
        "place, entity, a KB class (dbr:Cup) or values a|b|c"
    )


def configuration_of(question: str, fields: list[str]) -> str:
    """The ask role's configuration for a question and `name:TYPE` fields (checked: AskError)."""
    properties = dict(field_schema_of(spec) for spec in fields)
    configuration = json.dumps({"question": question, "result_schema_properties": properties})
    parse_configuration(configuration)
    return configuration


class Clarifying(BaseModel):
    """A field whose answer named several entities: the next answer chooses among them."""

    field: str
    candidates: list[str]


class FormState(BaseModel):
    """Where the form is: the values obtained, the field last asked, the tries per field."""

    values: dict[str, Any] = Field(default_factory=dict)
    asked: str | None = None
    clarifying: Clarifying | None = None
    tries: dict[str, int] = Field(default_factory=dict)
    #: Fields the person would not or could not give ("skip", "I don't know", too many tries).
    given_up: list[str] = Field(default_factory=list)
    status: Literal["open", "done", "cancelled"] = "open"

    @property
    def terminal(self) -> bool:
        return self.status != "open"

    def results(self) -> str:
        """The `results` JSON string: the fields obtained (the others are omitted, never invented)."""
        return json.dumps(self.values, ensure_ascii=False)

    def to_json(self) -> str:
        return self.model_dump_json()

    @classmethod
    def from_json(cls, text: str) -> FormState:
        return cls.model_validate_json(text) if text else cls()
