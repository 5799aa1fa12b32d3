"""Reading one field's value out of a clause of an answer: one finder per kind of field, in a table.

A finder says what value of its field a clause gives (`Found`), with the reason when the value said
cannot be used (a number out of bounds, a thing that is not of the field's class), or the
candidates when an entity field's words name several entities. None: the clause says nothing for
that field. Booleans and free strings are claimed only by the field being asked or named ("yes"
says nothing about a field nobody asked about), a boolean also by a clause opening with its yes or
no when the question asked for it among others; numbers, enum values and entities by their type.

>>> from dialogue.understanding.language import Language
>>> clause = Clause.of(Language.load("en"), "I'm twenty-three")
>>> clause.numbers
(Decimal('23'),)
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from decimal import Decimal
from typing import Any

from dialogue.ask.form import FieldKind, FormField
from dialogue.reference.english import tokens
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.lexicon import Lexicon, norm, singular
from dialogue.reference.resolution import ALL_KINDS, resolve
from dialogue.understanding.language import Language
from dialogue.understanding.said import Said


class _Words:
    """The language's words of answers (`ask.toml`; made once per language)."""

    def __init__(self, lang: Language) -> None:
        said = lang.ask
        self.yes = said.yes
        self.no = said.no
        #: No-words that turn a yes-word next to them into a no ("certainly not", "not true").
        self.negators = said.no - said.not_negators
        #: Words said before an answer that are not part of it ("it's Bob", "I'd like the red cup").
        self.lead_ins = said.lead_ins
        self.lead_in_text = said.lead_in_text
        #: A question back ("why do you want to know", "what do you mean", "pardon"), never a free
        #: string.
        self.question_back = said.question_back
        self.field_value = said.field_value
        #: Lead-in words kept in an answer's noun phrase ("my one", "the red one"), the one that
        #: makes it the speaker's, and those that say nothing of the choices offered.
        self.kept_lead_ins = said.kept_lead_ins
        self.owned = said.owned
        self.unqualifying = said.unqualifying
        #: Words by which the speaker names themself.
        self.self_ = said.self_
        self.ordinals = said.ordinals
        #: Said as a whole, these decide, the longest first: "why not" is a yes, "of course not" a no.
        self.boolean_phrases: tuple[tuple[tuple[str, ...], bool], ...] = tuple(
            (tuple(tokens(phrase)), value)
            for phrase, value in sorted(said.boolean_phrases.items(), key=lambda item: -len(item[0]))
        )


@dataclass(frozen=True)
class Clause:
    """A part of an answer: its text as said (case kept), its words, the numbers said in it."""

    text: str
    words: tuple[str, ...]
    #: Exact: a float would turn 400 nines into infinity and round 10**24 (``_number`` decides).
    numbers: tuple[Decimal, ...]
    #: The words as typed, an id whole ("cup_1").
    typed: tuple[str, ...] = ()

    @classmethod
    def of(cls, lang: Language, text: str) -> Clause:
        """The clause of `text`, its numbers read in `lang` (in words by text2num: "twenty-three")."""
        said = Said(lang, text)
        return cls(text.strip(), said.tokens, said.numbers, said.typed)

    def has(self, words: Sequence[str]) -> int | None:
        """Where `words` (singular or plural) occur in the clause, or None."""
        wanted, mine = norm(words), norm(self.words)
        for start in range(len(mine) - len(wanted) + 1):
            if mine[start : start + len(wanted)] == wanted:
                return start
        return None


@dataclass(frozen=True)
class Found:
    value: Any = None
    #: Why the value said cannot fill the field (then `value` is what was said).
    problem: str | None = None
    #: Several entities fit the words: the person is asked which.
    candidates: tuple[Entity, ...] = ()
    said: str = ""


@dataclass
class ReadContext:
    lexicon: Lexicon
    speaker: str
    #: The field the robot asked for last, the fields named in the clause.
    asked: str | None = None
    named: frozenset[str] = frozenset()
    #: Candidates of a clarifying question about this field, in the order they were offered.
    clarifying: dict[str, list[str]] = field(default_factory=dict)
    #: Other fields the robot's last question asked for (the form's own question asks for them all).
    covered: frozenset[str] = frozenset()


def checked(form_field: FormField, value: Any, said: str) -> Found:
    held, problem = form_field.check(value)
    return Found(value, problem, said=said) if problem else Found(held, said=said)


def _polarity(answer: _Words, words: Sequence[str]) -> list[bool]:
    """Each yes or no said in `words`; a yes-word with a negator beside it is one no."""
    said: list[bool] = []
    used: set[int] = set()
    for i, word in enumerate(words):
        if i in used or word not in answer.yes:
            continue
        around = [j for j in (i - 1, i + 1)
                  if 0 <= j < len(words) and words[j] in answer.negators and j not in used]  # fmt: skip
        used.update([i, *around[:1]])
        said.append(not around)
    said += [False for i, word in enumerate(words) if word in answer.no and i not in used]
    return said


def find_boolean(form_field: FormField, clause: Clause, ctx: ReadContext) -> Found | None:
    answer = ctx.lexicon.lang.derived(_Words)
    for phrase, value in answer.boolean_phrases:
        if clause.has(phrase) is not None:
            return Found(value, said=clause.text)
    said = set(_polarity(answer, clause.words))
    return Found(said.pop(), said=clause.text) if len(said) == 1 else None


def _number(form_field: FormField, clause: Clause) -> Found | None:
    if len(set(clause.numbers)) != 1:
        return None
    number = clause.numbers[0]
    whole = number == number.to_integral_value()
    if whole and form_field.kind == "integer":
        return checked(form_field, int(number), clause.text)
    as_float = float(number)
    if math.isfinite(as_float) and Decimal(repr(as_float)) == number:
        return checked(form_field, as_float, clause.text)
    if whole:  # exact as a JSON integer, where a float would round it (or overflow)
        return checked(form_field, int(number), clause.text)
    if form_field.kind == "integer":
        return checked(form_field, number, clause.text)  # a fraction: the check says so
    return Found(str(number), "it has more digits than can be kept exactly", said=clause.text)


def find_enum(form_field: FormField, clause: Clause, ctx: ReadContext) -> Found | None:
    hits: list[Any] = []
    for value in form_field.enum:
        if isinstance(value, bool):
            continue
        if isinstance(value, str):
            if clause.has(tokens(value)) is not None:
                hits.append(value)
        elif isinstance(value, int | float) and Decimal(repr(value)) in clause.numbers:
            hits.append(value)
    # "light blue" and "blue": the longest value said is the one meant.
    hits = [h for h in hits if not any(h != o and str(h) in str(o) for o in hits)]
    if not hits and (form_field.name == ctx.asked or form_field.name in ctx.named):
        hits = _by_a_word(ctx.lexicon.lang.derived(_Words), form_field, clause)
    return Found(hits[0], said=clause.text) if len(hits) == 1 else None


def _by_a_word(answer: _Words, form_field: FormField, clause: Clause) -> list[Any]:
    """ "chocolate" for "hot chocolate": the values one of whose words the clause says (answering
    this field only: a word is weak evidence)."""
    said = set(norm([w for w in clause.words if w not in answer.lead_ins]))
    return [v for v in form_field.enum if isinstance(v, str) and said & set(norm(tokens(v)))]


def find_string(form_field: FormField, clause: Clause, ctx: ReadContext) -> Found | None:
    answer = ctx.lexicon.lang.derived(_Words)
    text = clause.text
    if answer.question_back.match(text) or text.endswith("?"):  # "why do you want to know?" is no name
        return None
    start = clause.has(tokens(form_field.words)) if form_field.name in ctx.named else None
    if start is not None:  # "my name is Bob": what follows the field's words (and "is", ":")
        after = answer.field_value.split(text, maxsplit=1)
        text = after[1] if len(after) == 2 else ""
    text = answer.lead_in_text.sub("", text).strip(" \t,.;:!?\"'")
    return checked(form_field, text, clause.text) if text else None


def pool(form_field: FormField, snapshot: Snapshot) -> list[Entity]:
    """The entities the field may name: of its kinds and, when it has one, of its class."""
    return [
        e
        for e in snapshot.entities.values()
        if e.kind in form_field.kinds and (form_field.kb_class is None or form_field.kb_class in e.classes)
    ]


def find_entity(form_field: FormField, clause: Clause, ctx: ReadContext) -> Found | None:
    lexicon, snapshot = ctx.lexicon, ctx.lexicon.snapshot
    answer = lexicon.lang.derived(_Words)
    offered = [e for e in (snapshot.get(i) for i in ctx.clarifying.get(form_field.name, ())) if e is not None]
    choices = offered or pool(form_field, snapshot)
    ids = {e.id for e in choices}
    # An id typed as it is, used only when no noun phrase names a choice: an id may also be a word
    # ("cup" in the demo scene), and "the blue cup" means the blue one whatever the others are called.
    self_ = answer.self_
    typed = next((w for w in clause.typed if w in ids and w not in self_), None)
    if offered:
        for word, index in answer.ordinals.items():
            if word in clause.words:
                return Found(offered[index].id, said=word)
    # "myself" is the speaker, never the robot whose id it is.
    kept = answer.kept_lead_ins
    words = [w for w in clause.words if (w not in answer.lead_ins or w in kept) and w not in self_]
    owner = ctx.speaker if answer.owned & set(words) else None
    for start in range(len(words)):  # the noun phrase ends the clause: "I'd like the red cup"
        phrase = words[start:]
        found = resolve(lexicon, phrase, ALL_KINDS, owner=owner)
        if not found.matches:
            continue
        fits = [e for e in found.matches if e.id in ids]
        said = " ".join(phrase)
        if not fits and offered:  # "the red one": what the words say of the offered candidates
            fits = [
                e
                for e in offered
                if all(
                    singular(w) in lexicon.attributes.get(e.id, ())
                    for w in phrase
                    if w not in answer.unqualifying
                )
            ]
        if len(fits) == 1:
            return Found(fits[0].id, said=said)
        if fits:
            return Found(None, candidates=tuple(fits), said=said)
        if typed is not None:
            break
        what = form_field.kb_class or "/".join(sorted(form_field.kinds))
        return Found(said, problem=f"{said} is not a {_readable(what)}", said=said)
    if typed is not None:
        return Found(typed, said=typed)
    spoken = clause.words
    me = [i for i, w in enumerate(spoken) if w in self_ and not (i and spoken[i - 1] in answer.negators)]
    if ctx.speaker in ids and me:  # "to me" (not "not me"): the speaker, when the field may name them
        return Found(ctx.speaker, said=spoken[me[0]])
    return None


def _readable(kb_class: str) -> str:
    """ "dbr:Cup" -> "cup", "person/zone" stays."""
    name = kb_class.split(":")[-1].split("_(")[0].replace("_", " ")
    return re.sub(r"(?<=[a-z])(?=[A-Z])", " ", name).lower()


Finder = Callable[[FormField, Clause, ReadContext], "Found | None"]

FINDERS: dict[FieldKind, Finder] = {
    "boolean": find_boolean,
    "integer": lambda f, clause, ctx: _number(f, clause),
    "number": lambda f, clause, ctx: _number(f, clause),
    "enum": find_enum,
    "string": find_string,
    "entity": find_entity,
}
#: Kinds whose words say nothing about a field that is neither asked nor named ("yes", "Bob").
NEEDS_FOCUS: frozenset[FieldKind] = frozenset({"boolean", "string"})


def find(form_field: FormField, clause: Clause, ctx: ReadContext) -> Found | None:
    if form_field.kind in NEEDS_FOCUS and form_field.name != ctx.asked and form_field.name not in ctx.named:
        # A yes/no field the question asked for among others takes a clause that opens with its
        # yes or no: "I'm 34 and yes I love tea", "34, and no".
        if form_field.kind != "boolean" or form_field.name not in ctx.covered:
            return None
        return find_boolean(form_field, clause, ctx) if _opens_with_yes_or_no(clause, ctx) else None
    return FINDERS[form_field.kind](form_field, clause, ctx)


def _opens_with_yes_or_no(clause: Clause, ctx: ReadContext) -> bool:
    """Whether the clause's first word past its lead-ins ("well", "I"...) says yes or no, or one of
    the phrases that do ("of course not") starts it."""
    answer = ctx.lexicon.lang.derived(_Words)
    said = answer.yes | answer.no
    start = next((i for i, w in enumerate(clause.words) if w in said or w not in answer.lead_ins), None)
    if start is None:
        return False
    if clause.words[start] in said:
        return True
    return any(clause.has(phrase) == start for phrase, _ in answer.boolean_phrases)
