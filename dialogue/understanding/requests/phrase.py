"""A role's phrase as the grounding steps read it (dialogue.understanding.requests.ground): the words
prepared ("something to eat" is food, "it off the shelf" is "it", "the box of gloves not the
plasters" the box of gloves, "my mug the yellow one" my yellow mug), what they name worked out
once, and the question that asks which of several things they meant."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cached_property

from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.english import Words
from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.lexicon import singular
from dialogue.reference.resolution import Resolution, content_words, resolve
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome, Ref
from dialogue.understanding.replies import say
from dialogue.understanding.requests.referents import Referents
from dialogue.understanding.speech.clauses import described


@dataclass(frozen=True)
class Phrase:
    """A role's phrase as the steps read it, with what they read of it worked out once."""

    refs: Referents
    words: Words
    kinds: frozenset[Kind]
    role: str
    owner: str | None
    #: The request's other phrases, where a person pronoun finds the one person they name.
    said: Sequence[Words]

    @cached_property
    def content(self) -> list[str]:
        return content_words(self.refs.lang, self.words)

    @cached_property
    def resolved(self) -> Resolution:
        """What the phrase names (a description of several people is not the speaker's)."""
        sight = self.role != "object"  # a thing to fetch: of two towels, which is asked
        res = resolve(self.refs.lexicon, self.words, self.kinds, owner=self.owner, sight=sight)
        if res.ambiguous and any(e.id == self.refs.speaker for e in res.matches):
            # A speaker says "me", not "the person in the living room": a description is someone else.
            res = replace(res, matches=tuple(e for e in res.matches if e.id != self.refs.speaker))
        return res

    @cached_property
    def loose(self) -> Words:
        """The phrase without its spatial or comparative qualifiers, which the KB does not model."""
        return tuple(w for w in self.words if w not in self.refs.said.relational)

    @property
    def loosened(self) -> bool:
        """Whether qualifiers were dropped and something is left."""
        return self.loose != tuple(self.words) and bool(content_words(self.refs.lang, self.loose))

    def not_understood(self) -> Ref:
        return Ref(problem=Outcome(say(self.refs.lang, "sorry.not_understood"), understood=False))

    def which(self, matches: Sequence[Entity], words: Words) -> Ref:
        """The question that asks which of the matches the phrase meant."""
        refs = self.refs
        q = clarifying_question(refs.lang, refs.snapshot, matches, _noun(refs, words, matches))
        return Ref(problem=Outcome(q, clarify=True, open_role=self.role, open_phrase=words))


def prepared(refs: Referents, words: Words) -> Words:
    """The phrase as the steps read it: "something to eat" is food, "it off the shelf" is "it", "the
    box of gloves not the plasters" the box of gloves, "my mug the yellow one" my yellow mug."""
    lang = refs.lang
    bare_words = [w for w in words if w not in refs.said.determiners]
    something = bare_words[:1] in (["something"], ["anything"])
    wanted = refs.said.purpose(tuple(bare_words[1:])) if something else None
    if wanted is not None:  # "something to eat": food; "something to cut this with": a cutting tool
        words = wanted
    return _apposed(lang, _not_the_other(lang, _placed_pronoun(lang, words)))


def _noun(refs: Referents, words: Words, candidates: Sequence[Entity]) -> str | None:
    """The noun said for all the candidates ("a drink"), if the phrase ends its core with one."""
    core: list[str] = []
    for w in words:
        if w in refs.said.modifier_start and core:
            break
        core.append(w)
    content = content_words(refs.lang, core)
    if not content:
        return None
    noun = singular(content[-1])
    named = {n.entity for n in refs.lexicon.names_at([noun], 0) if len(n.words) == 1}
    return noun if all(c.id in named for c in candidates) else None


def _apposed(lang: Language, words: Words) -> Words:
    """ "my mug the yellow one": a second phrase of "one" says which the first is ("my yellow mug")."""
    if "one" not in words and "ones" not in words:
        return words
    for j in range(1, len(words)):
        np_start = lang.words.np_start
        if words[j] in np_start and words[j - 1] not in np_start and words[j - 1] not in lang.modifier_start:
            if "one" in words[j:] or "ones" in words[j:]:
                return described(lang, words[:j], words[j:])
            return words
    return words


def _placed_pronoun(lang: Language, words: Words) -> Words:
    """ "it off the shelf", "them from the table": the pronoun; where it is only says where to take it
    from (the thing is the one the conversation named)."""
    if len(words) > 2 and words[0] in lang.requests.referents.placed_pronouns and words[1] in lang.support:
        return words[:1]
    return words


def _not_the_other(lang: Language, words: Words) -> Words:
    """ "the box of gloves not the plasters": the thing meant, without the one it is not."""
    at = next((i for i in range(1, len(words)) if words[i] == "not" and words[i + 1 : i + 2]), None)
    return words if at is None or not content_words(lang, words[:at]) else words[:at]
