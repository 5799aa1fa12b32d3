"""The rules' grammar of questions about what people told: a fact of the answer with no object.

    what do I like · what does Alice like / love / enjoy   -> <person> likes ?
    what does Alice hate · what doesn't she like           -> <person> dislikes ?
    what's my name · who am I · do you know my name        -> <speaker> name ?
    what is her name · what is Alice's name                -> <person> name ?
    where is the diary (no place in the robot's knowledge) -> <thing> isIn ?

The answer comes from the robot's model, and from what others said when it has not adopted it
(dialogue.memory.learn): "where is the diary?" of a thing the robot has no place for, unseen, is
answered with what someone told ("Ines told me the diary is in the drawer"), kept as their belief
under the default trust policy. "Whose mug is this?" and "where are my keys?" are the situation questions
of the rules (dialogue.understanding.questions.grammar): what was adopted is in the situation like any fact.
"""

from __future__ import annotations

from collections.abc import Sequence

from dialogue.history import Utterance
from dialogue.reference.antecedent import antecedent
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import PERSON, THING, content_words, resolve
from dialogue.schema import FactClaim
from dialogue.understanding.said import Text
from dialogue.understanding.speech.repair import normalise

Words = tuple[str, ...]

class Asking:
    """Reads questions about told facts against a lexicon, for one speaker."""

    def __init__(self, lexicon: Lexicon, speaker: str, history: Sequence[Utterance] = ()) -> None:
        self.lexicon = lexicon
        self.lang = lexicon.lang
        self.said = lexicon.lang.questions.told
        #: "what is her name?": the possessive as the pronoun of the person just spoken of.
        self.pronoun_of: dict[Words, Words] = {(whose,): who for whose, who in self.said.pronoun_of.items()}
        self.speaker = speaker
        self.history = tuple(history)

    def read(self, text: Text) -> list[FactClaim] | None:
        w = tuple(normalise(self.lang, text))
        while w and w[-1] in self.said.tail:
            w = w[:-1]
        if w in self.said.who_am_i:
            return [FactClaim(subject=self.speaker, predicate="name", object=None)]
        unplaced = self._unplaced(w)
        if unplaced is not None:
            return [FactClaim(subject=unplaced, predicate="isIn", object=None)]
        name_of = self.said.name_of
        if name_of and w[: len(name_of)] == name_of and w[len(name_of) :]:  # "what is the name of Alice?"
            who = self._person(w[len(name_of) :])
            return [FactClaim(subject=who, predicate="name", object=None)] if who is not None else None
        what_is = self.said.what_is
        if what_is and w[: len(what_is)] == what_is and w[-1:] == ("name",) and len(w) > len(what_is) + 1:
            whose = w[len(what_is) : -1]  # "what is her name?"
            pronoun = self.pronoun_of.get(whose)
            who = self._person(pronoun) if pronoun is not None else self._owner(whose)
            return [FactClaim(subject=who, predicate="name", object=None)] if who is not None else None
        if w[:1] != ("what",) or len(w) < 4 or w[1] not in self.said.what_do:
            return None
        negated = w[1] == "don't" or w[-2:-1] == ("not",)
        verb = w[-1]
        subject = w[2:-2] if w[-2:-1] == ("not",) else w[2:-1]
        if verb in self.said.like:
            predicate = "dislikes" if negated else "likes"
        elif verb in self.said.hate and not negated:
            predicate = "dislikes"
        else:
            return None
        who = self._person(subject)
        return [FactClaim(subject=who, predicate=predicate, object=None)] if who is not None else None

    def _unplaced(self, w: Words) -> str | None:
        """The one thing "where is X" asks about when the robot knows no place for it nor sees it."""
        lead = next((p for p in self.said.where if w[: len(p)] == p), None)
        if lead is None:
            return None
        words = w[len(lead) :]
        if lead[-1] == "where" and words[-1:] and words[-1] in self.said.where_end:
            words = words[:-1]  # "do you know where the diary is"
        if not content_words(self.lang, words):
            return None
        found = resolve(self.lexicon, words, THING).one
        if found is None or found.kind != "thing" or found.seen:
            return None
        return None if found.support or found.zone or found.relations else found.id

    def _owner(self, words: Words) -> str | None:
        """The person of "Alice's" ("what is Alice's name?")."""
        if not words or not words[-1].endswith("'s"):
            return None
        return self._person((*words[:-1], words[-1][:-2]))

    def _person(self, words: Words) -> str | None:
        if words in self.said.speaker:
            return self.speaker
        if words in self.said.spoken_of:
            found = antecedent(self.lexicon, self.history, PERSON, speaker=self.speaker)
            return found.id if found is not None else None
        if not content_words(self.lang, words):
            return None
        found = resolve(self.lexicon, words, PERSON).one
        return found.id if found is not None else None
