"""Reading one field's value out of a clause of an answer: one finder per kind of field, in a table.

A finder says what value of its field a clause gives (`Found`), with the reason when the value said
cannot be used (a number out of bounds, a thing that is not of the field's class), or the
candidates when an entity field's words name several entities. None: the clause says nothing for
that field. Booleans and free strings are claimed only by the field being asked or named ("yes"
says nothing about a field nobody asked about); numbers, enum values and entities by their type.

>>> clause = Clause.of("I'm twenty-three")
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

from text_to_num import alpha2digit

from dialogue.ask.form import FieldKind, FormField
from dialogue.reference.english import tokens
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.reference.lexicon import Lexicon, norm, singular
from dialogue.reference.resolution import ALL_KINDS, resolve

YES = frozenset(
    {
        "yes",
        "yeah",
        "yep",
        "yup",
        "yea",
        "aye",
        "sure",
        "certainly",
        "definitely",
        "absolutely",
        "correct",
        "right",
        "true",
        "affirmative",
        "indeed",
        "ok",
        "okay",
        "alright",
        "course",
    }
)
NO = frozenset(
    {
        "no",
        "nope",
        "nah",
        "never",
        "negative",
        "false",
        "not",
        "don't",
        "dont",
        "doesn't",
        "isn't",
        "haven't",
        "hasn't",
        "wasn't",
        "aren't",
        "won't",
        "nothing",
        "none",
    }
)
#: Words said before an answer that are not part of it ("it's Bob", "I'd like the red cup").
LEAD_INS = frozenset(
    {
        "i",
        "i'm",
        "im",
        "i'd",
        "id",
        "am",
        "is",
        "it",
        "it's",
        "its",
        "that",
        "that's",
        "thats",
        "like",
        "want",
        "would",
        "take",
        "choose",
        "pick",
        "please",
        "well",
        "so",
        "um",
        "uh",
        "er",
        "hmm",
        "okay",
        "ok",
        "the",
        "a",
        "an",
        "say",
        "think",
        "guess",
        "maybe",
        "probably",
        "prefer",
        "rather",
        "have",
        "one",
        "answer",
        "call",
        "me",
        "they",
        "my",
        "name's",
        "years",
        "year",
        "old",
        "of",
        "course",
        "actually",
        "no",
        "sorry",
        "oh",
    }
)
_LEAD_IN_TEXT = re.compile(
    r"^(?:(?:well|so|um+|uh+|er|oh|ok(?:ay)?|yes|yeah|no|actually|sorry)\b[,\s]*)*"
    r"(?:(?:it'?s|it is|that'?s|that is|i'?m|i am|call me|they call me|i'?d say|i think|i guess|"
    r"the answer is|my answer is)\b\s*)?",
    re.IGNORECASE,
)
#: A question back ("why do you want to know", "what do you mean", "pardon"), never a free string.
QUESTION_BACK = re.compile(
    r"\s*(?:why|what|pardon|huh|come again|excuse me"
    r"|(?:can|could|would|will|do|did|does|are|is)\s+(?:you|i|we)|how\s+(?:do|does|did|can|come|about))\b",
    re.IGNORECASE,
)
_NUMBER = re.compile(r"(?<![\w.])((?:minus|negative)\s+|-)?(\d+(?:\.\d+)?)(?![\w]|\.\d)", re.IGNORECASE)
#: "one" after a determiner is a pronoun ("the red one", "that one"), not a number.
_PRONOUN_ONE = re.compile(
    r"\b(the|this|that|which|another|each|every|no|any)\b([^,;.]*?)\bone\b", re.IGNORECASE
)
#: Words by which the speaker names themself.
SELF = frozenset({"me", "myself"})
_THOUSANDS = re.compile(r"(?<=\d),(?=\d{3}\b)")
_HALF = re.compile(r"\b(\d+) and a half\b", re.IGNORECASE)
ORDINALS = {"first": 0, "second": 1, "third": 2, "fourth": 3, "last": -1}


@dataclass(frozen=True)
class Clause:
    """A part of an answer: its text as said (case kept), its words, the numbers said in it."""

    text: str
    words: tuple[str, ...]
    #: Exact: a float would turn 400 nines into infinity and round 10**24 (``_number`` decides).
    numbers: tuple[Decimal, ...]

    @classmethod
    def of(cls, text: str) -> Clause:
        digits = alpha2digit(_PRONOUN_ONE.sub("\\1\\2\u2060", text), "en", threshold=0)
        digits = _HALF.sub(r"\1.5", _THOUSANDS.sub("", digits))
        numbers = tuple((-1 if m.group(1) else 1) * Decimal(m.group(2)) for m in _NUMBER.finditer(digits))
        return cls(text.strip(), tuple(tokens(text)), numbers)

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


def checked(form_field: FormField, value: Any, said: str) -> Found:
    held, problem = form_field.check(value)
    return Found(value, problem, said=said) if problem else Found(held, said=said)


#: Said as a whole, these decide, the longest first: "why not" is a yes, "of course not" a no.
BOOLEAN_PHRASES: tuple[tuple[tuple[str, ...], bool], ...] = tuple(
    (tuple(tokens(phrase)), value)
    for phrase, value in sorted(
        {
            "of course not": False,
            "don't think so": False,
            "do not think so": False,
            "rather not": False,
            "why not": True,
            "no problem": True,
            "not a problem": True,
            "don't mind": True,
            "do not mind": True,
            "would love": True,
            "i'd love": True,
            "think so": True,
            "guess so": True,
            "go ahead": True,
            "please do": True,
        }.items(),
        key=lambda item: -len(item[0]),
    )
)
#: No-words that turn a yes-word next to them into a no ("certainly not", "not true").
NEGATORS = NO - {"no", "nope", "nah", "negative", "false", "nothing", "none"}


def _polarity(words: Sequence[str]) -> list[bool]:
    """Each yes or no said in `words`; a yes-word with a negator beside it is one no."""
    said: list[bool] = []
    used: set[int] = set()
    for i, word in enumerate(words):
        if i in used or word not in YES:
            continue
        around = [j for j in (i - 1, i + 1) if 0 <= j < len(words) and words[j] in NEGATORS and j not in used]
        used.update([i, *around[:1]])
        said.append(not around)
    said += [False for i, word in enumerate(words) if word in NO and i not in used]
    return said


def find_boolean(form_field: FormField, clause: Clause, ctx: ReadContext) -> Found | None:
    for phrase, value in BOOLEAN_PHRASES:
        if clause.has(phrase) is not None:
            return Found(value, said=clause.text)
    said = set(_polarity(clause.words))
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
        hits = _by_a_word(form_field, clause)
    return Found(hits[0], said=clause.text) if len(hits) == 1 else None


def _by_a_word(form_field: FormField, clause: Clause) -> list[Any]:
    """ "chocolate" for "hot chocolate": the values one of whose words the clause says (answering
    this field only: a word is weak evidence)."""
    said = set(norm([w for w in clause.words if w not in LEAD_INS]))
    return [v for v in form_field.enum if isinstance(v, str) and said & set(norm(tokens(v)))]


def find_string(form_field: FormField, clause: Clause, ctx: ReadContext) -> Found | None:
    text = clause.text
    if QUESTION_BACK.match(text) or text.endswith("?"):  # "why do you want to know?" is no name
        return None
    start = clause.has(tokens(form_field.words)) if form_field.name in ctx.named else None
    if start is not None:  # "my name is Bob": what follows the field's words (and "is", ":")
        after = re.split(r"\b(?:is|are|was|'s)\b|:", text, maxsplit=1)
        text = after[1] if len(after) == 2 else ""
    text = _LEAD_IN_TEXT.sub("", text).strip(" \t,.;:!?\"'")
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
    offered = [e for e in (snapshot.get(i) for i in ctx.clarifying.get(form_field.name, ())) if e is not None]
    choices = offered or pool(form_field, snapshot)
    ids = {e.id for e in choices}
    # An id typed as it is, used only when no noun phrase names a choice: an id may also be a word
    # ("cup" in the demo scene), and "the blue cup" means the blue one whatever the others are called.
    typed = next((w for w in re.findall(r"[\w:.\-()]+", clause.text) if w in ids and w not in SELF), None)
    if offered:
        for word, index in ORDINALS.items():
            if word in clause.words:
                return Found(offered[index].id, said=word)
    # "myself" is the speaker, never the robot whose id it is.
    words = [w for w in clause.words if (w not in LEAD_INS or w in ("my", "one")) and w not in SELF]
    owner = ctx.speaker if "my" in words else None
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
                    if w not in ("the", "one", "my")
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
    me = [i for i, w in enumerate(spoken) if w in SELF and not (i and spoken[i - 1] in NEGATORS)]
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
        return None
    return FINDERS[form_field.kind](form_field, clause, ctx)
