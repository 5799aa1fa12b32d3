"""Whose a role's phrase says its thing or place is: "go to my desk", "put it on Ana's shelf" (the
phrase without its possessive, and the owner, when that names one), and what a request for "my X"
says first when none of the things asked about is the speaker's ("Neither mug is yours. Which mug
do you mean...?")."""

from __future__ import annotations

from dataclasses import replace

from dialogue.reference.english import Words
from dialogue.reference.grounding import Kind
from dialogue.reference.resolution import content_words, resolve
from dialogue.understanding.context import Context
from dialogue.understanding.inflection import plural_of
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.replies import say


def whose(c: Context, words: Words, kinds: frozenset[Kind]) -> tuple[Words, str | None]:
    """ "go to my desk", "put it on Ana's shelf": a place said with whose it is, when that names
    one (a person's phrase keeps its possessive: "my son" is no son of the KB's)."""
    if not words or words[0] not in c.lang.words.possessives:  # "platform 4 my train's late": no one's
        return words, None
    if words[1:2] and words[1] in c.lang.modifier_start:  # "her in the bedroom": she, not hers
        return words, None
    bare, owner = c.refs.possessive(words, {})
    if owner is None or resolve(c.lexicon, bare, kinds, owner=owner).one is None:
        return words, None
    return bare, owner


def none_yours(c: Context, problem: Outcome, words: Words, kinds: frozenset[Kind]) -> Outcome:
    """ "give me my mug" when none of the mugs asked about is the speaker's: said so before
    asking which ("Neither mug is yours. Which mug do you mean...?")."""
    if not problem.clarify:
        return problem
    found = resolve(c.lexicon, words, kinds, sight=False).matches
    if len(found) < 2 or any(e.owner == c.speaker for e in found):
        return problem
    noun = content_words(c.lang, words)[-1]
    note = (say(c.lang, "naming.neither_yours", noun=noun) if len(found) == 2
            else say(c.lang, "naming.none_yours", nouns=plural_of(noun)))
    return replace(problem, reply=f"{note} {problem.reply}")
