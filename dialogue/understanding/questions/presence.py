"""Questions of comings and goings: "has Frances arrived?", "is Marta back yet?", "did Tom leave?",
"has Ade gone home?" — whether a person is here, answered from what the KB knows of them.

The KB knows a person is here when the robot sees them (`myself sees person_x`), and where they are
when a fact puts them in a place (`person_x isIn kitchen`, seen or told). The answer names the
person and says yes (seen), no (seen, to "has X left?"), what the KB last placed them in, or that
it does not know. A question about anyone or anything else is not this reader's: no answer.
"""

from __future__ import annotations

from dialogue.reference.english import Words
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import PERSON, resolve
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse
from dialogue.understanding.replies import location, say, the

#: The question kinds: whether someone has come, and whether someone has gone.
ARRIVED = "arrived"
DEPARTED = "departed"


class _Words:
    """The language's words of comings and goings (`questions.toml` [situation]), longest first."""

    def __init__(self, lang: Language) -> None:
        said = lang.questions.situation
        self.asking = said.presence_asking
        self.after = said.there_after
        come = [(phrase, ARRIVED) for phrase in said.arrived]
        gone = [(phrase, DEPARTED) for phrase in said.departed]
        self.ways = sorted([*come, *gone], key=lambda way: -len(way[0]))


def presence(lang: Language, w: Words) -> Parse | None:
    """The question "has X arrived?" or "did X leave?" (the auxiliary, the person, what they did,
    maybe "yet"), or None when the words are not one."""
    p = lang.derived(_Words)
    if not w[:1] or w[0] not in p.asking:
        return None
    said = w
    while len(said) > 2 and said[-1] in p.after:  # ("is Marta back yet?")
        said = said[:-1]
    for phrase, way in p.ways:
        if len(said) > len(phrase) + 1 and said[-len(phrase) :] == phrase:
            who = tuple(x for x in said[1 : -len(phrase)] if x not in p.after)  # ("has Tom already left?")
            if not who:
                return None
            return Parse("question", question=way, slots={"thing": who}, words=w)
    return None


def answer(lexicon: Lexicon, words: Words, speaker: str, way: str) -> str | None:
    """Whether the person is here, said with their name; None when the words are not one person
    the KB knows (other than the speaker)."""
    snapshot, lang = lexicon.snapshot, lexicon.lang
    who = resolve(lexicon, words, PERSON).one
    if who is None or who.id == speaker:
        return None
    name, where = the(lang, snapshot, who, speaker), location(lang, snapshot, who)
    there = f" {where}" if where else ""
    if who.seen:
        key = "answers.not_gone" if way == DEPARTED else "answers.has_come"
        return say(lang, key, name=name, where=there)
    if where:
        return say(lang, "answers.placed_unseen", name=name, where=where)
    return say(lang, "answers.presence_unknown", name=name)
