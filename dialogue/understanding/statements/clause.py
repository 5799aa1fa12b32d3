"""What every part of the statement grammar shares: the reader of a turn's clauses, its referents.

A `ClauseReader` holds one speaker's lexicon and history and grounds the phrases of a clause: an
entity of the wanted kinds ("the red mug", "my keys": whose it is said to be), or a person ("I",
"Alice", "she"). A phrase that names nothing leaves the clause to the other rules (`Unclaimed`), or
is refused with a reply ("Sorry, I don't know any umbrella.", a clarifying question: `Refused`).
The grammar itself is dialogue.understanding.statements.grammar (names, ownership, places) and
dialogue.understanding.statements.likings (preferences).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from dialogue.history import Utterance
from dialogue.reference.antecedent import antecedent
from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import PERSON, Resolution, content_words, is_pronoun, resolve
from dialogue.schema import FactClaim
from dialogue.understanding.replies import say

Words = tuple[str, ...]


@dataclass
class Told:
    """The rules' reading of a turn of statements: the facts, or the reply that says why none."""

    facts: list[FactClaim] = field(default_factory=list)
    reply: str | None = None
    clarify: bool = False
    greeted: bool = False


class Unclaimed(Exception):
    """A clause is not a statement this grammar reads: the turn is left to the other rules."""


class Refused(Exception):
    """A statement whose referent is unknown or ambiguous: the reply says so (no fact)."""

    def __init__(self, reply: str, clarify: bool = False) -> None:
        super().__init__(reply)
        self.reply = reply
        self.clarify = clarify


def fact(subject: str, predicate: str, obj: str | None) -> FactClaim:
    return FactClaim(subject=subject, predicate=predicate, object=obj)


class ClauseReader:
    """Grounds the phrases of statements against a lexicon, for one speaker and the dialogue's history."""

    def __init__(self, lexicon: Lexicon, speaker: str, history: Sequence[Utterance] = (),
                 overrides: Mapping[Words, Words] | None = None) -> None:
        self.lexicon = lexicon
        self.lang = lexicon.lang
        self.snapshot = lexicon.snapshot
        self.speaker = speaker
        #: Phrases read as other words: an ambiguous one completed by the answer to the robot's
        #: question (dialogue.understanding.followups.statement).
        self.overrides = dict(overrides or {})
        #: The phrase the last clarifying question was about.
        self.open_phrase: Words | None = None
        self.history = tuple(history)

    def _person(self, words: Words) -> str | None:
        if words in self.lang.statements.speaker_subject:
            return self.speaker
        if words in self.lang.statements.spoken_of:
            found = antecedent(self.lexicon, self.history, PERSON, speaker=self.speaker)
            return found.id if found is not None else None
        if not content_words(self.lang, words) or not all(w.isalpha() for w in words):
            return None
        res = resolve(self.lexicon, words, PERSON)
        if res.ambiguous:
            raise Refused(clarifying_question(self.lang, self.snapshot, res.matches), clarify=True)
        return res.one.id if res.one is not None else None

    def _entity(self, words: Words, kinds: frozenset[Kind],
                fits: Callable[[Entity], bool] | None = None) -> tuple[str, str | None]:
        """One entity of `kinds` the phrase names, and whose it is said to be ("my keys"). With
        `fits`, only an entity it accepts: any other phrase, or a pronoun, is not this grammar's."""
        self.open_phrase, words = words, self.overrides.get(words, words)
        if "person" in kinds and words in self.lang.statements.speaker_person:
            return self.speaker, None
        possessives = self.lang.words.possessives
        said = [w for w in words if w in possessives]
        owner = self.speaker if said[:1] in (["my"], ["our"]) else None
        bare = tuple(w for w in words if w not in possessives)
        if not content_words(self.lang, bare) or is_pronoun(self.lang, bare):
            found = None if fits is not None else antecedent(
                self.lexicon, self.history, kinds, speaker=self.speaker
            )
            if found is None and fits is not None:
                raise Unclaimed
            if found is None:
                raise Refused(say(self.lang, "sorry.what_meant", phrase=" ".join(words)), clarify=True)
            return found.id, owner
        res = resolve(self.lexicon, bare, kinds, owner=owner)
        if fits is not None:
            res = Resolution(res.phrase, tuple(e for e in res.matches if fits(e)))
            if not res.matches:
                raise Unclaimed
        if res.one is not None:
            return res.one.id, owner
        if res.ambiguous:
            raise Refused(clarifying_question(self.lang, self.snapshot, res.matches), clarify=True)
        if any(not self.lexicon.knows(w) for w in content_words(self.lang, bare)) and any(
            self.lexicon.knows(w) for w in content_words(self.lang, bare)
        ):
            raise Unclaimed  # names the KB knows among words it does not: leave it to a model
        raise Refused(say(self.lang, "sorry.unknown", phrase=" ".join(content_words(self.lang, bare))))
