"""Whether a request is for now: negated ("don't go"), or said under a condition yet to happen, first
("if I nod off, could you...", "when the bell goes, ...") or after it ("say hi to her when she comes
in"), not a polite "if" or "when you get a chance"."""

from __future__ import annotations

from collections.abc import Sequence

from dialogue.reference.english import Words
from dialogue.understanding.language import Language
from dialogue.understanding.requests.vocabulary import Grammar
from dialogue.understanding.speech.plain import starts, strip_politeness
from dialogue.understanding.speech.repair import asked_verb


def negation(g: Grammar, words: Sequence[str]) -> bool:
    return words[0] in g.negators or (bool(g.negation) and starts(words, g.negation))


def conditional(g: Grammar, words: Sequence[str]) -> bool:
    """Whether the request is said under a condition of something to happen first ("if I nod off,
    could you..."), not a polite "if" ("if you could...", "if I could have the bill")."""
    if words[:1] != ["if"] or len(words) < 4 or g.polite_if.of(words):
        return False
    return words[2] not in g.if_modals


#: How many words of a condition may say it is the robot's own time ("you have got a minute").
_YOUR_TIME = 5


def later(lang: Language, words: list[str]) -> bool:
    """Whether a request is said after a condition yet to happen ("when the bell goes, could you...",
    "after lunch take me to the day room", "when the train stops get my rucksack down")."""
    g = lang.derived(Grammar)
    said = g.conditions.first(words)
    if said is None or len(words) < len(said) + 2 or words[len(said)] in g.not_conditions:
        return False
    if any(starts(words, p) for p in g.adjuncts_by_first.get(words[0], ())):  # "when you get a chance"
        return False
    clause = words[len(said) : len(said) + _YOUR_TIME]
    if clause[:1] == ["you"] and set(clause) & g.your_time:  # "when you've got a minute, ..."
        return False
    for i in range(len(said) + 1, len(words)):
        rest = strip_politeness(lang, words[i:])
        if rest and (rest != words[i:] or asked_verb(lang, words[i]) is not None):
            # ("..., could you take", "... get my rucksack down", "... pour me a tea")
            return asked_verb(lang, rest[0]) is not None
    return False


def when(g: Grammar, adjuncts: tuple[Words, ...]) -> bool:
    """Whether a clause of time after the request says when it is to be done, later ("say hi to her
    *when she comes in*"), rather than how long or while what ("while he waits")."""
    return any(len(a) > len(c) and a[len(c)] in g.their_subjects for a in adjuncts
               for c in g.conditions.of(a)) or any(_absent(g, a) for a in adjuncts)  # fmt: skip


#: How many words of a clause of time may say the speaker is away ("while we are both out").
_ABSENT = 4


def _absent(g: Grammar, adjunct: Words) -> bool:
    """Whether a clause of time is the speaker's absence yet to come ("while I'm out")."""
    if len(adjunct) < 3 or adjunct[0] not in g.while_ or adjunct[1] not in g.absent_speakers:
        return False
    return bool(set(adjunct[2 : 2 + _ABSENT]) & g.absences)
