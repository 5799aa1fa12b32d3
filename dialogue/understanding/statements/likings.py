"""The statement grammar's likings: "I like tea", "Alice hates coffee", "I'm fond of tea", "tea is my
favourite", "I don't like the radio" -> <person> likes / dislikes <kind or thing>.

The object is a thing of the situation when the phrase names one with a determiner ("the radio"),
a person, the robot ("I like you"), or else the words of a kind ("tea", "apples"), found among the
KB's classes when learnt. A liking of what happens or of doing something ("I like it when you
dance", "I like to dance", "I hate waiting") or a bare "that" is no statement.
"""

from __future__ import annotations

from lemminflect import getAllLemmas

from dialogue.reference.english import word_set
from dialogue.reference.resolution import ANYWHERE
from dialogue.schema import FactClaim
from dialogue.understanding.statements.clause import ClauseReader, Unclaimed, Words, fact

_INTENSIFIERS = word_set("really truly absolutely quite totally just")
_LIKE = word_set("like likes love loves enjoy enjoys adore adores prefer prefers")
_HATE = word_set("hate hates dislike dislikes detest detests loathe loathes")
#: Whole leads that say a liking of what follows ("I'm fond of tea", "I'm not a fan of coffee").
_LEADS: dict[Words, str] = {
    **{tuple(f"i am {p} of".split()): "likes" for p in ("fond", "a fan", "a big fan", "a huge fan")},
    **{tuple(f"i am {p} of".split()): "dislikes"
       for p in ("not fond", "not a fan", "no fan", "not a big fan")},
    ("i", "cannot", "stand"): "dislikes",
}
_FAVOURITE = word_set("favourite favorite")
#: What a preference is over ("I prefer tea to coffee").
_OVER = word_set("to over than")
#: A liking of what happens or of doing something ("I like it when...", "I like to dance"): no thing.
_HAPPENINGS = word_set("it to when whenever if how what where while")
#: A bare "this", "that": an appraisal of what just happened or was said, not of a thing.
_APPRAISED: frozenset[Words] = frozenset({("this",), ("that",), ("these",), ("those",), ("them",)})
#: Words that start a clause inside the object ("I like the way you talk").
_CLAUSE = word_set("i you he she we they when whenever if because while")


class Likings(ClauseReader):
    def _preference(self, w: Words, clause: str) -> list[FactClaim] | None:
        w = tuple(x for x in w if x not in _INTENSIFIERS)
        for lead, predicate in _LEADS.items():
            if w[: len(lead)] == lead and w[len(lead) :]:
                return [fact(self.speaker, predicate, self._liked(w[len(lead) :]))]
        favourite = self._favourite(w)
        if favourite is not None:
            return [fact(self.speaker, "likes", self._liked(favourite))]
        for cut in range(1, min(len(w) - 1, 4)):  # the subject: one to three words
            verb, negated = cut, False
            if w[cut : cut + 2] in {("do", "not"), ("does", "not")}:
                verb, negated = cut + 2, True
            elif w[cut] == "don't":
                verb, negated = cut + 1, True
            if verb + 1 >= len(w):
                continue
            if w[verb] in _LIKE:
                predicate = "dislikes" if negated else "likes"
            elif w[verb] in _HATE and not negated:
                predicate = "dislikes"
            else:
                continue
            who = self._person(w[:cut])
            if who is not None:
                liked = w[verb + 1 :]
                if w[verb].startswith("prefer"):  # "I prefer tea to coffee": a liking of tea
                    liked = next((liked[:i] for i, x in enumerate(liked) if x in _OVER), liked)
                return [fact(who, predicate, self._liked(liked))]
        return None

    @staticmethod
    def _favourite(w: Words) -> Words | None:
        """What "tea is my favourite (drink)" or "my favourite drink is tea" says the speaker likes."""
        if w[:2] in {("my", f) for f in _FAVOURITE} and "is" in w[2:4]:
            return w[w.index("is", 2) + 1 :] or None
        for i in range(1, len(w) - 2):
            if w[i : i + 2] == ("is", "my") and w[i + 2] in _FAVOURITE:
                return w[:i]
        return None

    def _liked(self, words: Words) -> str:
        """A thing of the situation when the phrase names one with a determiner ("the radio"), else
        the words of a kind ("tea", "apples"), found among the KB's classes when learnt."""
        words = tuple(w for w in words if w not in {"very", "much", "really", "so", "a", "lot", "too"})
        if words and words[0].endswith("ing") and "VERB" in getAllLemmas(words[0]):
            raise Unclaimed  # "I hate marking lab reports": an activity, no thing or kind of the KB
        if not words or words[0] in _HAPPENINGS or words in _APPRAISED or _CLAUSE & set(words[1:]):
            raise Unclaimed  # "I like it when you dance", "I like to dance", "I like that": no thing
        if words and words[0] in {"the", "this", "that", "my", "your", "his", "her"}:
            return self._entity(words, ANYWHERE)[0]
        if words in {("you",), ("yours",)}:
            return self.snapshot.robot
        person = self._person(words) if words[:1] != ("it",) else None
        if person is not None:
            return person
        return " ".join(words)
