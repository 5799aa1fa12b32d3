"""The offline reading of one answer to the ask role: which fields it fills, corrects or refuses.

An answer is cut into clauses ("I'm 34 and my name is Bob", "the red cup, and yes"); each clause
fills one field: the field it names ("my age is 34"), else the field being clarified, else the field
asked, else the one open field its value fits (a number, an enum value, an entity of the field's
class; a yes or no opening a clause, "I'm 34 and yes I love tea", when the form's own question asked
for every field and one yes/no field is open), else — when the answer corrects ("no, I'm 34",
"actually...") — the one filled field it fits.
A value its field cannot hold is a problem (said back, then asked again), several entities a
clarifying question. "Never mind" cancels the form; "I don't know" or "skip" gives up the field.

>>> from dialogue.ask.form import parse_configuration
>>> from dialogue.reference.grounding import build_snapshot
>>> from dialogue.reference.lexicon import Lexicon
>>> from dialogue.understanding.language import Language
>>> from kb import KB
>>> form = parse_configuration('{"question": "Age and pets?", "result_schema_properties": '
...     '{"age": {"type": "integer", "minimum": 0}, "pets": {"type": "boolean"}}}')
>>> lexicon = Lexicon(build_snapshot(KB()), Language.load("en"))
>>> read_answer(form, FormState(asked="age"), "thirty-four, and no", lexicon, "alice").values
{'age': 34, 'pets': False}
>>> read_answer(form, FormState(asked="pets"), "nope", lexicon, "alice").values
{'pets': False}
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from dialogue.ask.fields import Clause, Found, ReadContext, find
from dialogue.ask.form import AskForm, Clarifying, FormState
from dialogue.reference.english import tokens
from dialogue.reference.grounding import Entity
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.said import Said, Text


@dataclass
class Reading:
    """What one answer says about the form."""

    values: dict[str, Any] = field(default_factory=dict)
    #: Field -> why what was said cannot fill it.
    problems: dict[str, str] = field(default_factory=dict)
    clarify: Clarifying | None = None
    clarify_options: tuple[Entity, ...] = ()
    cancel: bool = False
    skipped: list[str] = field(default_factory=list)
    #: What the reading did, for the turn's trace.
    notes: list[str] = field(default_factory=list)

    @property
    def understood(self) -> bool:
        return bool(self.values or self.problems or self.clarify or self.cancel or self.skipped)


def _named(form: AskForm, clause: Clause) -> frozenset[str]:
    return frozenset(f.name for f in form.fields if clause.has(tokens(f.words)) is not None)


def _choose(
    form: AskForm,
    state: FormState,
    reading: Reading,
    found: dict[str, Found],
    named: frozenset[str],
    correcting: bool,
) -> str | None:
    """The field a clause fills, among those whose finder found something in it (module docstring).

    A free string fits any words, so it is the weakest reading: the field asked takes the clause as
    a string only when no number in it fits another field and the answer corrects nothing."""
    usable = {name for name, f in found.items() if f.problem is None} or set(found)
    filled = set(state.values) | set(reading.values)
    strings = {n for n in usable if form.field(n).kind == "string"}
    typed = usable - strings
    number = any(form.field(n).kind in ("integer", "number") for n in typed)
    clarifying = state.clarifying.field if state.clarifying is not None else None
    tiers = [
        [n for n in usable if n == clarifying],
        [n for n in form.names if n in usable and n in named],
        [n for n in typed if n == state.asked],
        [n for n in strings if n == state.asked and not number and not correcting],
        [n for n in typed if n not in filled and n not in state.given_up],
        [n for n in typed if correcting and n in filled],
        [n for n in strings if n == state.asked],
    ]
    for index, names in enumerate(tiers):
        if len(names) == 1 or (names and index == 1):  # between named fields, the form's order decides
            return names[0]
        if names:
            return None  # several fit equally: not guessed
    return None


def _covered(form: AskForm, state: FormState) -> frozenset[str]:
    """The fields besides the one asked that the robot's last question asked for: all of them when
    it was the form's own question, none when it was a field's own or a clarifying question."""
    asked = state.asked
    if asked not in form.names or state.clarifying is not None or not form.own_question_for(asked):
        return frozenset()
    return frozenset(n for n in form.names if n != asked)


def read_answer(form: AskForm, state: FormState, answer: Text, lexicon: Lexicon, speaker: str) -> Reading:
    """What an answer to the form fills, corrects, refuses or gives up, and whether it cancels."""
    reading = Reading()
    heard = Said.read(lexicon.lang, answer)
    text = heard.text
    said = lexicon.lang.ask.answers  # (cancel, skip, corrections, where an answer is cut)
    if said.cancel.search(text):
        reading.cancel = True
        reading.notes.append(f"cancelled: {text!r}")
        return reading
    words = list(heard.tokens)
    asked = form.field(state.asked) if state.asked in form.names else None
    # "no, I'm 34" corrects; a bare "no" to a yes/no question answers it.
    correcting = (
        bool(words)
        and words[0] in said.correction
        and not (
            asked is not None
            and asked.kind == "boolean"
            and asked.name not in state.values
            and len(words) == 1
        )
    )
    clarifying = {state.clarifying.field: state.clarifying.candidates} if state.clarifying else {}
    # A leading "no" that may correct a value given before answers no other field; before any value,
    # there is nothing to correct ("no I don't, and I'm 30").
    covered = frozenset() if correcting and state.values else _covered(form, state)
    for part in said.split.split(text):
        if not part.strip():
            continue
        clause = Clause.of(lexicon.lang, part)
        named = _named(form, clause)
        if said.skip.search(part):
            target = next((n for n in form.names if n in named), state.asked)
            if target is not None and target not in reading.values:
                reading.skipped.append(target)
                reading.notes.append(f"{target}: given up ({part.strip()!r})")
            continue
        ctx = ReadContext(lexicon, speaker, state.asked, named, clarifying, covered)
        found = {f.name: hit for f in form.fields if (hit := find(f, clause, ctx)) is not None}
        target = _choose(form, state, reading, found, named, correcting)
        if target is None:
            if found:
                reading.notes.append(f"{part.strip()!r} fits {sorted(found)}: not used")
            continue
        _take(reading, state, target, found[target])
    return reading


def _take(reading: Reading, state: FormState, name: str, hit: Found) -> None:
    if hit.candidates:
        reading.clarify = Clarifying(field=name, candidates=[e.id for e in hit.candidates])
        reading.clarify_options = hit.candidates
        reading.notes.append(f"{name}: {hit.said!r} names {len(hit.candidates)} entities; asking which")
        return
    if hit.problem is not None:
        reading.problems[name] = hit.problem
        reading.notes.append(f"{name}: {hit.said!r} refused: {hit.problem}")
        return
    before = state.values.get(name)
    reading.values[name] = hit.value
    reading.problems.pop(name, None)
    verb = "corrected" if name in state.values and before != hit.value else "filled"
    reading.notes.append(f"{name}: {verb} with {hit.value!r} (from {hit.said!r})")
