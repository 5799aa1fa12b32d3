"""The statement grammar's likings: "I like tea", "Alice hates coffee", "I'm fond of tea", "tea is my
favourite", "I don't like the radio" -> <person> likes / dislikes <kind or thing>.

The object is a thing of the situation when the phrase names one with a determiner ("the radio"),
a person, the robot ("I like you"), or else the words of a kind ("tea", "apples"), found among the
KB's classes when learnt. A liking of what happens or of doing something ("I like it when you
dance", "I like to dance", "I hate waiting") or a bare "that" is no statement.
"""

from __future__ import annotations

from functools import cached_property

from dialogue.reference.resolution import ANYWHERE
from dialogue.schema import FactClaim
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.said import Said
from dialogue.understanding.statements.clause import ClauseReader, Unclaimed, Words, fact


class _Words:
    """The language's words of likings (`statements.toml` [likings]; made once per language)."""

    def __init__(self, lang: Language) -> None:
        said = lang.statements.likings
        self.intensifiers = said.intensifiers
        self.like = said.like
        self.hate = said.hate
        #: Whole leads that say a liking of what follows ("I'm fond of tea", "I'm not a fan of coffee").
        self.leads = said.leads
        self.favourite = said.favourite
        #: What a preference is over ("I prefer tea to coffee").
        self.over = said.over
        #: A liking of what happens or of doing something ("I like it when...", "I like to dance").
        self.happenings = said.happenings
        #: A bare "this", "that": an appraisal of what just happened or was said, not of a thing.
        self.appraised = said.appraised
        #: Words that start a clause inside the object ("I like the way you talk").
        self.clause = said.clause
        #: What negates the verb ("I do not like", "Bo doesn't like"): a phrase, or one word.
        self.negation = said.negation
        self.negated = said.negated
        #: "tea is my favourite": what comes between the thing and `favourite`.
        self.is_my = said.is_my
        #: Words of degree around the thing liked ("very much", "a lot", "too").
        self.degree = said.degree
        #: Words before a thing of the situation ("the radio", "my mug"), and that name the robot.
        self.determined = said.determined
        self.robot = said.robot


class Likings(ClauseReader):
    @cached_property
    def liked(self) -> _Words:
        """The language's words of likings (asked ~18 times a turn: looked up once per reader)."""
        return self.lang.derived(_Words)

    def _preference(self, w: Words, clause: Said) -> list[FactClaim] | None:
        w = tuple(x for x in w if x not in self.liked.intensifiers)
        for lead, predicate in self.liked.leads.items():
            if w[: len(lead)] == lead and w[len(lead) :]:
                return [fact(self.speaker, predicate, self._liked(w[len(lead) :]))]
        favourite = self._favourite(w)
        if favourite is not None:
            return [fact(self.speaker, "likes", self._liked(favourite))]
        for cut in range(1, min(len(w) - 1, 4)):  # the subject: one to three words
            verb, negated = cut, False
            negation = next((n for n in self.liked.negation if w[cut : cut + len(n)] == n), None)
            if negation is not None:
                verb, negated = cut + len(negation), True
            elif w[cut] in self.liked.negated:
                verb, negated = cut + 1, True
            if verb + 1 >= len(w):
                continue
            if w[verb] in self.liked.like:
                predicate = "dislikes" if negated else "likes"
            elif w[verb] in self.liked.hate and not negated:
                predicate = "dislikes"
            else:
                continue
            who = self._person(w[:cut])
            if who is not None:
                liked = w[verb + 1 :]
                if w[verb].startswith("prefer"):  # "I prefer tea to coffee": a liking of tea
                    liked = next((liked[:i] for i, x in enumerate(liked) if x in self.liked.over), liked)
                return [fact(who, predicate, self._liked(liked))]
        return None

    def _favourite(self, w: Words) -> Words | None:
        """What "tea is my favourite (drink)" or "my favourite drink is tea" says the speaker likes."""
        if w[:2] in {("my", f) for f in self.liked.favourite} and "is" in w[2:4]:
            return w[w.index("is", 2) + 1 :] or None
        for i in range(1, len(w) - 2):
            if self.liked.is_my and w[i : i + 2] == self.liked.is_my and w[i + 2] in self.liked.favourite:
                return w[:i]
        return None

    def _liked(self, words: Words) -> str:
        """A thing of the situation when the phrase names one with a determiner ("the radio"), else
        the words of a kind ("tea", "apples"), found among the KB's classes when learnt."""
        words = tuple(w for w in words if w not in self.liked.degree)
        if words and words[0].endswith("ing") and "VERB" in lemmas_of(words[0]):
            raise Unclaimed  # "I hate marking lab reports": an activity, no thing or kind of the KB
        liked = self.liked
        happening = words[:1] and words[0] in liked.happenings
        if not words or happening or words in liked.appraised or liked.clause & set(words[1:]):
            raise Unclaimed  # "I like it when you dance", "I like to dance", "I like that": no thing
        if words and words[0] in liked.determined:
            return self._entity(words, ANYWHERE)[0]
        if len(words) == 1 and words[0] in liked.robot:
            return self.snapshot.robot
        person = self._person(words) if words[:1] != ("it",) else None
        if person is not None:
            return person
        return " ".join(words)
