"""The LLM answer: pydantic models (validation) and the per-turn JSON schema (constrained decoding).

The shape follows the ROS4HRI tutorial (`verbal_ack` + `user_intent`), with one change: `input` holds
the free-form value of an intent (the words to SAY, an activity/motion/content name), so that
`object`, `recipient` and `goal` are always KB ids and can be enums of the turn's candidate ids.
Small models ignore enums, so every answer is validated again and resolved against the KB.

The schema offered to a model is as short to write as the answer allows, since a grammar-constrained
small model writes every token the grammar leaves open: an intent type by its short name ("grab_object"
for `__intent_grab_object__`), each intent with only the keys its type takes, several intents as a
list in `user_intent`, and no optional key, so the answer ends after its last required key. What is
parsed is wider: the tutorial's full type names and `user_intents`, which other backends (the rules)
and users' own models may write.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from dialogue.errors import DialogueError
from dialogue.intents import CATALOGUE, EXTRACTABLE

#: Referent fields of `user_intent`; their values must be KB entity ids.
REFERENT_FIELDS = ("object", "recipient", "goal")
#: Intents whose `object` is free-form text, written in `input` (the words to SAY, an activity name).
FREE_FORM_OBJECT = frozenset(
    {
        "__intent_say__",
        "__intent_start_activity__",
        "__intent_stop_activity__",
        "__intent_perform_motion__",
        "__intent_present_content__",
    }
)
#: The order of an intent's keys in the schema: "type" first, what is acted on next.
_KEY_ORDER = ("object", "input", "recipient", "goal")


def short_name(intent: str) -> str:
    """The name a model writes for an intent type: "grab_object" for `__intent_grab_object__`."""
    return intent.removeprefix("__intent_").removesuffix("__")


def full_name(name: str) -> str:
    """The catalogue's value of a short name; any other text (a full name, an unknown one) as it is."""
    full = f"__intent_{name}__"
    return full if full in CATALOGUE else name


def intent_keys(intent: str) -> tuple[str, ...]:
    """The answer keys of an intent type (its roles; free-form text in `input`), required ones first
    in the prompt, in `_KEY_ORDER` in the schema."""
    spec = CATALOGUE[intent]
    roles = [r for r in spec.roles if r != "other_data"]
    return tuple("input" if r == "object" and intent in FREE_FORM_OBJECT else r for r in roles)


class UserIntent(BaseModel):
    """What the model understood the user wants; every field may be null."""

    model_config = ConfigDict(extra="ignore")

    type: str | None = None
    object: str | None = None
    recipient: str | None = None
    goal: str | None = None
    input: str | None = None
    #: Not in the JSON schema offered to LLMs (kept small); offline models may set it.
    confidence: float | None = Field(default=None, ge=0.0, le=1.0)

    @field_validator("type")
    @classmethod
    def _full_type(cls, value: str | None) -> str | None:
        return None if value is None else full_name(value)


#: Most intents one answer may carry ("go to the kitchen, take the plate and bring it to me").
MAX_INTENTS = 4
#: Most facts one answer may carry ("I'm Bob and the red mug is mine").
MAX_FACTS = 4
#: The predicates of `facts` (dialogue.memory.claims holds what each means).
FACT_PREDICATES = ("name", "belongsTo", "isIn", "isOn", "likes", "dislikes")


class FactClaim(BaseModel):
    """Something the person tells the robot (`object` given) or asks it (`object` null) about the
    world: `subject` and `object` are KB ids ("me": the speaker), or for a name the name itself."""

    model_config = ConfigDict(extra="ignore")

    subject: str | None = None
    predicate: str | None = None
    object: str | None = None


class ChatbotResponse(BaseModel):
    """The whole answer: a short spoken reply and the intents, in the order they are to be done.

    `user_intent` is the ROS4HRI tutorial's single intent; `user_intents`, when given and not empty,
    is the ordered list of every intent of a compound request and takes its place. A list written
    in `user_intent` (the schema's way of saying several) is that list.
    """

    model_config = ConfigDict(extra="ignore")

    verbal_ack: str | None = None
    user_intent: UserIntent | None = None
    user_intents: list[UserIntent] | None = Field(default=None, max_length=MAX_INTENTS)
    #: What the person told (or asked) about the world, learnt by dialogue.memory.
    facts: list[FactClaim] | None = Field(default=None, max_length=MAX_FACTS)

    @model_validator(mode="before")
    @classmethod
    def _several_in_user_intent(cls, value: Any) -> Any:
        if isinstance(value, dict) and isinstance(value.get("user_intent"), list):
            several = value["user_intent"]
            value = {**value, "user_intent": several[0] if several else None}
            if not value.get("user_intents"):
                value["user_intents"] = several
        return value

    def wishes(self) -> list[UserIntent]:
        """Every intent of the answer, in order (the list, else the single intent)."""
        if self.user_intents:
            return [w for w in self.user_intents if w.type is not None]
        return [self.user_intent] if self.user_intent is not None and self.user_intent.type else []


class AnswerError(DialogueError, ValueError):
    """The model's content is not a usable answer; the message says why (it is sent back in a repair)."""


def extract_json(content: str) -> Any:
    """Decode the first JSON value starting at the first `{`, string-aware (D2); text is never rewritten."""
    start = content.find("{")
    if start < 0:
        raise AnswerError("the answer contains no JSON object")
    try:
        value, _end = json.JSONDecoder().raw_decode(content, start)
    except json.JSONDecodeError as exc:
        raise AnswerError(f"the answer is not valid JSON ({exc.msg} at character {exc.pos})") from None
    return value


Answer = TypeVar("Answer", bound=BaseModel)


def validated(content: str, model: type[Answer], keys: str) -> Answer:
    """The raw content's JSON object validated into `model`, or AnswerError saying what is wrong
    (never anything else, D3); `keys` names the object's keys for the message."""
    value = extract_json(content)
    if not isinstance(value, dict):
        raise AnswerError(f"the answer must be a JSON object with keys {keys}")
    try:
        return model.model_validate(value)
    except ValidationError as exc:
        problems = "; ".join(
            f"{'.'.join(str(p) for p in err['loc']) or 'answer'}: {err['msg']}" for err in exc.errors()
        )
        raise AnswerError(f"the answer does not match the schema ({problems})") from None


def parse_answer(content: str) -> ChatbotResponse:
    """Validate the raw content into a ChatbotResponse or raise AnswerError (never anything else, D3)."""
    return validated(content, ChatbotResponse, "verbal_ack and user_intent")


@dataclass(frozen=True)
class SchemaCandidates:
    """The ids the model may use this turn, per referent field (already bounded by the grounding)."""

    objects: Sequence[str]
    recipients: Sequence[str]
    goals: Sequence[str]


def _nullable_enum(values: Sequence[str]) -> dict[str, Any]:
    if not values:
        return {"type": "null"}
    return {"enum": [*values, None]}


#: Longest free text a model may write in one field: a grammar-constrained small model otherwise
#: runs on ("____...") until max_tokens and the answer is truncated.
MAX_TEXT = 200


def _nullable_string() -> dict[str, Any]:
    return {"anyOf": [{"type": "string", "maxLength": MAX_TEXT}, {"type": "null"}]}


def _intent(intent: str, candidates: SchemaCandidates) -> dict[str, Any]:
    """One intent type's object: its short name, then only the keys it takes (each may be null)."""
    referents = {"object": candidates.objects, "recipient": candidates.recipients, "goal": candidates.goals}
    keys = intent_keys(intent)
    properties: dict[str, Any] = {"type": {"const": short_name(intent)}}
    for key in sorted(keys, key=_KEY_ORDER.index):
        properties[key] = _nullable_string() if key == "input" else _nullable_enum(referents[key])
    return {"type": "object", "properties": properties, "required": list(properties)}


def turn_schema(candidates: SchemaCandidates, intents: Sequence[str] = EXTRACTABLE) -> dict[str, Any]:
    """The JSON schema of this turn's answer: intent types and referents are closed enums (D10).

    Every key is required and none is optional, so a grammar made from it ends the answer after
    `facts` (a small model otherwise goes on writing optional keys: ~200 tokens a turn)."""
    one = {"anyOf": [_intent(intent, candidates) for intent in intents]}
    many = {"type": "array", "items": one, "minItems": 2, "maxItems": MAX_INTENTS}
    fact = {
        "type": "object",
        "properties": {
            "subject": _nullable_enum(candidates.goals),
            "predicate": {"enum": list(FACT_PREDICATES)},
            # An id of the situation, or words: a name ("Bob"), a kind of thing ("tea").
            "object": {"anyOf": [*([{"enum": list(candidates.goals)}] if candidates.goals else []),
                                 *_nullable_string()["anyOf"]]},
        },
        "required": ["subject", "predicate", "object"],
    }
    facts = {"type": "array", "items": fact, "minItems": 1, "maxItems": MAX_FACTS}
    return {
        "type": "object",
        "properties": {
            "verbal_ack": _nullable_string(),
            # One intent, several in order (a compound request), or none.
            "user_intent": {"anyOf": [{"type": "null"}, *one["anyOf"], many]},
            # What the person told about themself or the world (dialogue.memory), mostly null.
            "facts": {"anyOf": [{"type": "null"}, facts]},
        },
        "required": ["verbal_ack", "user_intent", "facts"],
    }
