"""What was said in a turn, read once: the `Said` every stage of the offline understanding reads.

The rules model makes one per turn (dialogue.understanding.readers) and hands it to each reader; a
stage that reads words takes it (or, called on its own, a text it makes one of: `Said.read`). It
holds

    text       the words as said (or as a stage rewrote them: letters joined, slips corrected)
    marked     each token, comma and semicolon with its start and end in the text: the text's one
               scan by the one tokeniser (reference.english)
    spans      each token with its start and end (`marked` less the marks)
    tokens     the tokens alone
    taken      what words were taken for: each slip corrected, with the word it was read as
    written    the words as written: the text cut at white space, casing and punctuation kept
               (`unquoted`: with double quotes read as white space), for what keeps the casing
    quoted     where the text quotes (each quote's start and end in the text)
    typed      the words as typed, an id whole ("cup_1", "dbr:Table_(furniture)")
    numbers    the numbers the words say, in digits or in words ("twenty-three", "minus three")

and the forms the stages derive from it (`form`: the speech forms expanded, the plain words, the
normalised words, the clauses, the text with its self-repairs resolved), each made once. The texts a
stage cuts out of it (a clause, a part of a compound request, the text after a repair) are of the
same turn (`of`): read once too, however many readers and stages read them; a word of it read as a
text of its own (`word`) is its own one token, never scanned again. A form is made of the
language's data and the text alone, never of the KB: the same words read the same in every reader.
(The conversation before the turn is dialogue.history's: its utterances are texts, read when read.)
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from decimal import Decimal
from functools import cached_property
from typing import Any, TypeVar

from text_to_num import alpha2digit

from dialogue.reference.english import MARKS, Words, spans
from dialogue.understanding.language import Language

T = TypeVar("T")
#: A quote: the words between double quotes, straight or curly.
QUOTED = re.compile(r"[\"\u201c\u201d]([^\"\u201c\u201d]+)[\"\u201c\u201d]")
#: Double quotes, read as white space where the words are taken as written ('"Bob" Smith').
_DOUBLE_QUOTES = str.maketrans({q: " " for q in '"“”«»'})
#: A word as typed, an id whole.
_TYPED = re.compile(r"[\w:.\-()]+")


@dataclass(frozen=True)
class Taken:
    """A word read as another: "teh" taken for "the", "thremos" for "thermos"."""

    said: str
    taken_for: str
    #: The word was read as a name of the KB: which thing is meant is a guess.
    guess: bool = False


class Said:
    """One text of a turn, and what has been read of it."""

    def __init__(
        self, lang: Language, text: str, taken: tuple[Taken, ...] = (), turn: dict[str, Said] | None = None
    ) -> None:
        self.lang = lang
        self.text = text
        self.taken = taken
        #: The turn's texts read so far, this one among them (`of`).
        self._turn = turn if turn is not None else {}
        self._turn.setdefault(text, self)
        self._forms: dict[Callable[[Said], Any], Any] = {}

    @staticmethod
    def read(lang: Language, text: Text) -> Said:
        """What a stage reads of a text: the text of a turn as it is, any other text on its own."""
        return text if isinstance(text, Said) else Said(lang, text)

    def __repr__(self) -> str:
        return f"Said({self.text!r})"

    def of(self, text: str) -> Said:
        """Another text read in the same turn (a clause, a part of it, or an utterance before it
        that a stage reads again: the request a follow-up answers), read once."""
        said = self._turn.get(text)
        return said if said is not None else Said(self.lang, text, self.taken, self._turn)

    def word(self, token: str) -> Said:
        """One of the turn's tokens as a text of its own: a token is its own one token, so it is
        not scanned again."""
        said = self._turn.get(token)
        if said is None:
            said = Said(self.lang, token, self.taken, self._turn)
            # What scanning it would give, set at once (each of the three, made on first use, is
            # four calls through cached_property's lock: a turn reads its words one by one).
            marked = ((token, 0, len(token)),)
            spanned = () if token in MARKS else marked
            said.__dict__.update(marked=marked, spans=spanned, tokens=(token,) if spanned else ())
        return said

    def rewritten(self, text: str, taken: tuple[Taken, ...] = ()) -> Said:
        """The turn as a stage rewrote it: what it took words for added to what was taken before."""
        if text == self.text and not taken:
            return self
        return Said(self.lang, text, (*self.taken, *taken), self._turn)

    @cached_property
    def marked(self) -> tuple[tuple[str, int, int], ...]:
        return tuple(spans(self.text, marks=True))

    @cached_property
    def spans(self) -> tuple[tuple[str, int, int], ...]:
        return tuple(s for s in self.marked if s[0] not in MARKS)

    @cached_property
    def tokens(self) -> Words:
        return tuple(w for w, _, _ in self.spans)

    @cached_property
    def written(self) -> Words:
        return tuple(self.text.split())

    @cached_property
    def unquoted(self) -> Words:
        return tuple(self.text.translate(_DOUBLE_QUOTES).split())

    @cached_property
    def quoted(self) -> tuple[tuple[int, int], ...]:
        return tuple(m.span() for m in QUOTED.finditer(self.text))

    @cached_property
    def typed(self) -> Words:
        return tuple(_TYPED.findall(self.text))

    @cached_property
    def numbers(self) -> tuple[Decimal, ...]:
        """Exact: a float would turn 400 nines into infinity and round 10**24. "One" after a
        determiner is a pronoun ("the red one"), never a number."""
        said = self.lang.ask
        digits = alpha2digit(said.pronoun_one.sub("\\1\\2\u2060", self.text), self.lang.code, threshold=0)
        digits = said.half.sub(r"\1.5", said.thousands.sub("", digits))
        return tuple((-1 if m.group(1) else 1) * Decimal(m.group(2)) for m in said.number.finditer(digits))

    @property
    def guessed(self) -> bool:
        """Whether a word was read as a name of the KB: which thing is meant is a guess."""
        return any(t.guess for t in self.taken)

    def form(self, make: Callable[[Said], T]) -> T:
        """A form of the words (`make` of this text, immutable), made on first use."""
        try:  # (a subscript, no other call: the stages ask for the same forms ~25 times a turn)
            made: T = self._forms[make]
        except KeyError:
            made = self._forms[make] = make(self)
        return made


#: What a stage reads: a text of the turn, or a text read on its own.
Text = Said | str
