"""The form after an answer, and what the robot says next: the next question, a problem said back,
a clarifying question, or the end (every required field obtained, given up or cancelled).

A field that could not be obtained after `MAX_TRIES` answers is given up: the form ends without it
(its key is omitted from the results, never invented).

>>> from dialogue.ask.form import parse_configuration
>>> from dialogue.understanding.followups.form import Reading
>>> form = parse_configuration('{"question": "How old are you?", "result_schema_properties": '
...     '{"age": {"type": "integer", "minimum": 0, "maximum": 130}}}')
>>> state = opening_state(form)
>>> state, line = advance(form, state, Reading(problems={"age": "Input should be less than or equal to 130"}))
>>> line
'That is not a possible age: it must be at least 0 and at most 130. How old are you?'
>>> state, line = advance(form, state, Reading(values={"age": 34}))
>>> state.status, state.results(), line
('done', '{"age": 34}', 'Thank you.')
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from dialogue.ask.fields import pool
from dialogue.ask.form import AskForm, Clarifying, FieldKind, FormField, FormState
from dialogue.reference.clarify import MAX_OPTIONS, describe_options
from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.followups.form import Reading
from dialogue.understanding.language import Language
from dialogue.understanding.replies import say, template

MAX_TRIES = 3


def opening_state(form: AskForm) -> FormState:
    """The form before any answer: asking its first required field (the first field when none is
    required: the question is asked once, and its answer ends the form)."""
    missing = _missing(form, FormState())
    return FormState(asked=missing[0] if missing else form.fields[0].name)


def _missing(form: AskForm, state: FormState) -> list[str]:
    return [n for n in form.required if n not in state.values and n not in state.given_up]


def _language(lexicon: Lexicon | None) -> Language:
    """The turn's language (its lexicon's); a form used without one speaks the packaged default."""
    return lexicon.lang if lexicon is not None else Language.load()


def _join(lang: Language, options: Sequence[str], word: str = "or") -> str:
    if len(options) == 1:
        return options[0]
    return ", ".join(options[:-1]) + f" {say(lang, 'ask.' + word)} " + options[-1]


def bounds(form_field: FormField, lang: Language | None = None) -> str:
    """What a number field accepts, said ("at least 0 and at most 130")."""
    lang = lang or Language.load()
    schema = form_field.schema
    said = [str(w).format(value=schema[k]) for k, w in template(lang, "ask.bounds").items() if k in schema]
    return f" {say(lang, 'ask.and')} ".join(said)


def problem_line(form_field: FormField, problem: str, lang: Language | None = None) -> str:
    lang = lang or Language.load()
    field = form_field.words
    # (the problem is what the schema's validation said: pydantic's messages, in English)
    if form_field.kind == "integer" and "fractional part" in problem:  # pydantic's int_from_float
        return say(lang, "ask.not_whole", field=field)
    if form_field.kind in ("integer", "number") and bounds(form_field, lang) and " than " in problem:
        return say(lang, "ask.out_of_bounds", field=field, bounds=bounds(form_field, lang))
    if form_field.kind == "enum":
        return say(lang, "ask.only", field=field, options=_join(lang, [str(v) for v in form_field.enum]))
    if form_field.kind == "entity":
        return say(lang, "ask.entity_problem", problem=problem)
    return say(lang, "ask.not_possible", field=field, problem=problem.lower())


def _options(lexicon: Lexicon, entities: Sequence[Entity]) -> list[str]:
    """How the choices are said: people by their names, things by what tells them apart."""
    if entities and all(e.kind == "person" for e in entities):
        return [e.name for e in entities]
    return describe_options(lexicon.lang, lexicon.snapshot, entities)


#: What the form's own question is followed by when it is asked again, by the field's kind.
_HINTS: dict[FieldKind, Callable[[Language, FormField], str]] = {
    "boolean": lambda lang, f: " " + say(lang, "ask.hint_boolean"),
    "enum": lambda lang, f: " " + say(lang, "ask.hint_enum", options=_join(lang, [str(v) for v in f.enum])),
}


#: How a field other than the first is asked, by its kind (given the entities' options, if listed).
_QUESTIONS: dict[FieldKind, Callable[[Language, FormField, list[str]], str]] = {
    "boolean": lambda lang, f, _options: say(lang, "ask.ask_boolean", field=f.words),
    "enum": lambda lang, f, _options: say(
        lang, "ask.ask_enum", field=f.words, options=_join(lang, [str(v) for v in f.enum])
    ),
    "entity": lambda lang, f, options: (
        say(lang, "ask.ask_entity", field=f.words, options=_join(lang, options))
        if options
        else say(lang, "ask.ask_entity_open", field=f.words)
    ),
}


def _open_question(lang: Language, form_field: FormField, _options: list[str]) -> str:
    return say(lang, "ask.ask_open", field=form_field.words)


def _listed(form_field: FormField, snapshot: Snapshot | None) -> list[Entity]:
    """The entities a question about an entity field lists (all it may name, when they are few)."""
    choices = pool(form_field, snapshot) if snapshot is not None else []
    return choices if 1 < len(choices) <= MAX_OPTIONS else []


def asking(form: AskForm, name: str, lexicon: Lexicon | None = None) -> tuple[str, list[Entity]]:
    """How the robot asks for one field — its description when it is a question, the form's question
    for the first field, else by the field's kind — and the entities the question offers."""
    form_field = form.field(name)
    description = form_field.schema.get("description")
    if isinstance(description, str) and description.strip().endswith("?"):
        return description.strip(), []
    lang = _language(lexicon)
    if form.own_question_for(name):
        hint = _HINTS.get(form_field.kind)
        return form.question + (hint(lang, form_field) if hint else ""), []
    snapshot = lexicon.snapshot if lexicon is not None else None
    listed = _listed(form_field, snapshot) if form_field.kind == "entity" else []
    options = _options(lexicon, listed) if lexicon is not None and listed else []
    return _QUESTIONS.get(form_field.kind, _open_question)(lang, form_field, options), listed


def question_for(form: AskForm, name: str, lexicon: Lexicon | None = None) -> str:
    """How the robot asks for one field (`asking`)."""
    return asking(form, name, lexicon)[0]


def advance(
    form: AskForm,
    state: FormState,
    reading: Reading,
    lexicon: Lexicon | None = None,
    options: Sequence[Entity] = (),
) -> tuple[FormState, str]:
    """The form once `reading` is applied, and the robot's next line."""
    lang = _language(lexicon)
    new = state.model_copy(deep=True)
    if reading.cancel:
        new.status, new.asked, new.clarifying = "cancelled", None, None
        return new, say(lang, "ask.cancelled")
    new.values.update(reading.values)
    for name in reading.values:
        new.tries.pop(name, None)
        if name in new.given_up:
            new.given_up.remove(name)
    if new.clarifying is not None and new.clarifying.field in reading.values:
        new.clarifying = None
    new.given_up += [n for n in reading.skipped if n not in new.given_up and n not in new.values]
    _count_tries(new, reading)
    lines: list[str] = []
    for name, problem in reading.problems.items():
        if name not in reading.values:
            lines.append(problem_line(form.field(name), problem, lang))
    if not reading.understood and state.asked is not None:
        lines.append(say(lang, "ask.not_understood"))
    if reading.clarify is not None and reading.clarify.field not in new.given_up:
        new.clarifying, new.asked = reading.clarify, reading.clarify.field
        if lexicon is not None and options:
            return new, " ".join([*lines, clarifying_question(lexicon.lang, lexicon.snapshot, options)])
    missing = _missing(form, new)
    if not missing:
        new.status, new.asked, new.clarifying = "done", None, None
        return new, say(lang, "ask.done" if new.values else "ask.done_empty")
    if new.clarifying is not None and new.clarifying.field in missing and lexicon is not None:
        offered = [e for e in (lexicon.snapshot.get(i) for i in new.clarifying.candidates) if e is not None]
        if offered:
            new.asked = new.clarifying.field
            return new, " ".join([*lines, clarifying_question(lexicon.lang, lexicon.snapshot, offered)])
    new.asked = new.asked if new.asked in missing else missing[0]
    line, offered = asking(form, new.asked, lexicon)
    # The entities the question lists are the choices, in the order said ("the second one").
    new.clarifying = Clarifying(field=new.asked, candidates=[e.id for e in offered]) if offered else None
    return new, " ".join([*lines, line])


def _count_tries(state: FormState, reading: Reading) -> None:
    """An answer that gave the asked field nothing usable counts as a try; too many give it up."""
    tried: set[str] = set(reading.problems)
    if state.asked is not None and state.asked not in reading.values and reading.clarify is None:
        tried.add(state.asked)
    for name in tried - set(reading.values) - set(state.given_up):
        state.tries[name] = state.tries.get(name, 0) + 1
        if state.tries[name] >= MAX_TRIES:
            state.given_up.append(name)
            if state.clarifying is not None and state.clarifying.field == name:
                state.clarifying = None
