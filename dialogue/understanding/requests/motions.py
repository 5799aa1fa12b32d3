"""An activity asked for by the name of one of the robot's motions ("do a dance for me", "can you do
a little dance", "give us a wave") is that motion, not an activity beyond its skills: which motions
the robot has are the verbs of the frames that perform one with the verb as its text
(`frames.toml`: "dance|wave|nod|bow|...")."""

from __future__ import annotations

from dataclasses import replace

from dialogue import intents as I
from dialogue.reference.english import phrases
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.parsed import Parse
from dialogue.understanding.requests.frames import TEXTS, frames


def motions(lang: Language) -> frozenset[str]:
    """The one-word motions of the robot's motion frames (read once per language)."""
    return lang.derived(_motions)


def _motions(lang: Language) -> frozenset[str]:
    return frozenset(
        verb[0]
        for f in frames(lang)
        if f.intent == I.PERFORM_MOTION and f.text is TEXTS["verb"]
        for verb in phrases(f.verbs)
        if len(verb) == 1
    )


def as_motion(lang: Language, p: Parse) -> Parse:
    """The motion an activity's last word names ("a little dance": dance), as the motion frame reads
    it; the parse as it was when the activity names none."""
    said = p.slots.get("activity")
    if p.intent != I.START_ACTIVITY or not said:
        return p
    noun = said[-1]
    motion = next((m for m in (noun, *lemmas_of(noun).get("NOUN", ())) if m in motions(lang)), None)
    if motion is None:
        return p
    slots = {role: words for role, words in p.slots.items() if role != "activity"}
    return replace(p, intent=I.PERFORM_MOTION, slots=slots, text=motion)
