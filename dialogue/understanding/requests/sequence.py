"""A compound request read part by part ("go to the kitchen and take the plate"): what each part
asks for, in order, and what the parts say together.

Each part is read as a request of its own, with the parts before it as context for its pronouns
("take the book and put it in the oven"). A part whose verb the robot has no intent for ("... and
find the newspaper") does not sink the others: they are done and the reply says which part cannot
be. A part read without full evidence makes the whole a proposal (each part said back in it).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.understanding.context import Reader
from dialogue.understanding.followups.proposal import proposed
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.replies import say, then
from dialogue.understanding.requests.compound import Part
from dialogue.understanding.said import Said


def compound(reader: Reader, heard: Said, parts: Sequence[Part]) -> Outcome | None:
    """Every part read in order: the intents, or the question about a part that must come first, or
    None when a part is not understood (the whole is then read otherwise)."""
    done: list[Outcome] = []
    cannot: list[str] = []
    context: list[Utterance] = []
    aside = False
    for n, part in enumerate(parts):
        within = reader.within((*reader.history, *context))
        context.append(Utterance(reader.speaker, part.text))
        if n == 0 and part.verb is None:
            continue  # a preamble ("hey there", "thanks", "the denim jacket"): context for the rest
        if part.aside and n < len(parts) - 1:
            aside = True  # "move out of the way and go to the door": the going does it
            continue
        outcome = within.part(heard.of(part.text))
        if outcome.intent is not None and done and (outcome.intent, outcome.roles) == (
            done[-1].intent, done[-1].roles):
            continue  # "go to the shed and wait there": one move
        if outcome.intent is not None:
            done.append(outcome)
            if outcome.roles.get("object") in reader.snapshot.entities:
                # "get the teddy off the bench and give it to Zara": "it" is what was taken
                context.append(Utterance(reader.speaker, outcome.roles["object"]))
        elif outcome.clarify:
            return outcome  # ask about this part first: nothing is done until it is clear
        elif part.no_intent:
            cannot.append(part.text)
        else:  # a part that fails says why; one not understood makes the whole not understood
            return outcome if outcome.understood else None
    if not done or (aside and not {o.intent for o in done} & {I.MOVE_TO, I.GUIDE}):
        return None  # (out of the way, then no going anywhere: not understood)
    lang = reader.lang
    acks = [then(lang, [o.reply for o in done])]
    unable = [say(lang, "request.cannot", action=c) for c in cannot]
    whole = replace(done[0], reply=" ".join([*acks, *unable]), more=tuple(done[1:]))
    if whole.doubts:  # each part said back in the question
        return proposed(lang, whole, [o.reply for o in done], unable)
    return whole
