"""The ask role with a model: the per-turn JSON schema (the form's own schema, entity fields as enums
of KB ids), the prompt, and the validation of the answer into a `Reading`.

The answer is ``{"answers": {FIELD: value | null}, "cancel": bool, "verbal_ack": str | null}``,
validated with pydantic; each value is checked against its field's schema and each entity re-resolved
against the KB (small models ignore enums). What the model got wrong (not JSON, a value of the wrong
type, an id the KB does not have) goes back to it once in a repair request; a value the field cannot
hold because of what the person said (out of bounds, not one of the values) is said back to them.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel, ConfigDict, ValidationError

from dialogue.ask.fields import Clause, ReadContext, find, pool
from dialogue.ask.form import AskForm, Clarifying, FormField, FormState
from dialogue.history import Utterance
from dialogue.llm.base import ChatMessage
from dialogue.prompts import PromptSet, history_message, load_template, render
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import resolve_id
from dialogue.schema import MAX_TEXT, AnswerError, validated
from dialogue.situation import describe
from dialogue.understanding.followups.form import Reading

MAX_IDS = 60
#: Keys of a field's schema that are not JSON Schema (or not for the model).
_NOT_FOR_MODEL = frozenset({"x-kb-class", "format", "title"})


class AskAnswer(BaseModel):
    model_config = ConfigDict(extra="ignore")

    verbal_ack: str | None = None
    answers: dict[str, Any] | None = None
    cancel: bool | None = False


def field_schema(form_field: FormField, ids: Sequence[str]) -> dict[str, Any]:
    """What the model may put in one field: the configured schema, an entity as an enum of ids."""
    if form_field.kind == "entity":
        return {"enum": list(ids)} if ids else {"type": "null"}
    schema = {k: v for k, v in form_field.schema.items() if k not in _NOT_FOR_MODEL}
    if form_field.kind == "string":
        schema["maxLength"] = min(int(schema.get("maxLength", MAX_TEXT)), MAX_TEXT)
    return schema


def entity_ids(form: AskForm, snapshot: Snapshot, focus: Sequence[Entity]) -> dict[str, list[str]]:
    """Per entity field, the ids it may take, the turn's most relevant first, capped."""
    order = {e.id: i for i, e in enumerate(focus)}
    out = {}
    for f in form.fields:
        if f.kind == "entity":
            choices = sorted(pool(f, snapshot), key=lambda e: order.get(e.id, len(order)))
            out[f.name] = [e.id for e in choices[:MAX_IDS]]
    return out


def ask_schema(form: AskForm, ids: dict[str, list[str]]) -> dict[str, Any]:
    """The JSON schema of this turn's answer (constrained decoding)."""
    answers = {
        f.name: {"anyOf": [field_schema(f, ids.get(f.name, ())), {"type": "null"}]} for f in form.fields
    }
    return {
        "type": "object",
        "properties": {
            "answers": {"type": "object", "properties": answers, "required": list(form.names)},
            "cancel": {"type": "boolean"},
            "verbal_ack": {"anyOf": [{"type": "string", "maxLength": MAX_TEXT}, {"type": "null"}]},
        },
        "required": ["answers", "cancel", "verbal_ack"],
    }


def _describe_field(form_field: FormField, ids: Sequence[str]) -> str:
    schema = form_field.schema
    if form_field.kind == "entity":
        what = f"the id of one of: {', '.join(f'[{i}]' for i in ids[:12])}" if ids else "none available"
    elif form_field.kind == "enum":
        what = "one of " + ", ".join(json.dumps(v) for v in form_field.enum)
    else:
        limits = [
            f"{k} {schema[k]}"
            for k in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum", "maxLength", "pattern")
            if k in schema
        ]
        what = form_field.kind + (f" ({', '.join(limits)})" if limits else "")
    description = schema.get("description")
    return f"- {form_field.name}: {what}" + (f". {description}" if isinstance(description, str) else "")


@dataclass(frozen=True)
class AskPrompts:
    """The ask role's templates (files in the `prompts` package); load once, render every turn."""

    system: Any
    turn: Any
    repair: Any

    @classmethod
    def load(cls, package: str = "prompts") -> AskPrompts:
        return cls(*(load_template(name, package) for name in ("ask_system", "ask_turn", "ask_repair")))

    def messages(
        self,
        form: AskForm,
        state: FormState,
        ids: dict[str, list[str]],
        *,
        robot_name: str,
        speaker: str,
        text: str,
        history: Sequence[Utterance],
        locale: str | None,
        snapshot: Snapshot,
        focus: Sequence[Entity],
        language: PromptSet,
    ) -> tuple[ChatMessage, ...]:
        fields = "\n".join(_describe_field(f, ids.get(f.name, ())) for f in form.fields)
        system = render(
            self.system, {"robot_name": robot_name, "question": form.question, "field_list": fields}
        )
        situation = ""
        if ids:  # the situation only for a form that names entities of the KB
            situation = "Current situation:\n" + describe(snapshot, speaker, focus).text + "\n\n"
        missing = [n for n in form.required if n not in state.values and n not in state.given_up]
        turn = render(
            self.turn,
            {
                "situation": situation,
                "user_id": speaker,
                "input": text,
                "filled": json.dumps(state.values, ensure_ascii=False),
                "missing": ", ".join(missing) or "none",
            },
        )
        turn += language.language_line(locale)
        return (
            ChatMessage("system", system),
            *(history_message(u) for u in history),
            ChatMessage("user", turn),
        )

    def repair_message(self, errors: str) -> ChatMessage:
        return ChatMessage("user", render(self.repair, {"errors": errors}))


def parse_ask_answer(content: str) -> AskAnswer:
    return validated(content, AskAnswer, '"answers", "cancel" and "verbal_ack"')


#: pydantic error types that mean the model wrote a value of the wrong type (its fault, not the person's).
_TYPE_ERRORS = ("_type", "_parsing", "bool_", "int_from_float")


def _value(form_field: FormField, value: Any, lexicon: Lexicon, speaker: str, reading: Reading) -> None:
    name = form_field.name
    if form_field.kind == "entity":
        choices = {e.id for e in pool(form_field, lexicon.snapshot)}
        found = resolve_id(lexicon, str(value).strip(), form_field.kinds)
        fits = [e for e in found.matches if e.id in choices]
        if len(fits) == 1:
            reading.values[name] = fits[0].id
        elif fits:
            reading.clarify = Clarifying(field=name, candidates=[e.id for e in fits])
            reading.clarify_options = tuple(fits)
        else:
            raise AnswerError(
                f"answers.{name} {value!r} is not the id of an entity the field may take; "
                f"use one of {sorted(choices)[:30]} or null"
            )
        return
    try:
        reading.values[name] = form_field.validator().validate_python(value)
    except ValidationError as exc:
        errors = exc.errors()
        if isinstance(value, str):  # "34 years": what the rules read in the words
            hit = find(form_field, Clause.of(lexicon.lang, value), ReadContext(lexicon, speaker, asked=name))
            if hit is not None and hit.problem is None and not hit.candidates:
                reading.values[name] = hit.value
                return
        if any(any(t in str(e["type"]) for t in _TYPE_ERRORS) for e in errors):
            raise AnswerError(
                f"answers.{name}: {errors[0]['msg']} (the field is {form_field.kind})"
            ) from None
        reading.problems[name] = "; ".join(str(e["msg"]) for e in errors)


def reading_of(answer: AskAnswer, form: AskForm, state: FormState, lexicon: Lexicon, speaker: str) -> Reading:
    """The model's answer as a Reading of the form (AnswerError: what to repair)."""
    reading = Reading()
    if answer.cancel:
        reading.cancel = True
        reading.notes.append("cancelled (the model's reading)")
        return reading
    errors = []
    for name, value in (answer.answers or {}).items():
        if name not in form.names:
            reading.notes.append(f"ignored unknown field {name!r}")
            continue
        if value is None or (name in state.values and state.values[name] == value):
            continue
        try:
            _value(form.field(name), value, lexicon, speaker, reading)
        except AnswerError as exc:
            errors.append(str(exc))
    if errors:
        raise AnswerError("; ".join(errors))
    for name, value in reading.values.items():
        verb = "corrected" if name in state.values else "filled"
        reading.notes.append(f"{name}: {verb} with {value!r} (model)")
    for name, problem in reading.problems.items():
        reading.notes.append(f"{name}: refused: {problem} (model)")
    return reading
