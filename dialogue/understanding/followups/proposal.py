"""A reading proposed, not acted on: the confirmation question and its answer.

When the rules read a request without full evidence for it (a word they cannot account for, a
question that may only ask what the robot can do: `Outcome.unsure`), they never act on it: they
propose it ("Shall I bring the soap to Jordan?", `proposed`), the intents held in the question's
`proposal`. The next turn answers it (`answered`): "yes", "sure", "please do" act on the reading
proposed; "no" drops it (the grammar's refusal); anything else is a new turn.

The proposal lives where every other follow-up finds what it answers, in the dialogue's history: the
robot's question is its latest utterance, the request right before it is read again in the
conversation it was said in, and it is acted on only when that reading still proposes the very
question asked (a KB that changed since makes it a new turn).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from dialogue.understanding.context import Reader
from dialogue.understanding.followups.accepting import accepts
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.replies import say, template

#: How sure a reading acted on after its confirmation is (said whole, then confirmed).
CONFIRMED_CONFIDENCE = 0.8


def action_said(lang: Language, reply: str) -> str:
    """An acknowledgement said as the action a question proposes ("OK, I will bring the cup to you."
    -> "bring the cup to you")."""
    for start, instead in template(lang, "confirm.starts"):
        if reply.startswith(str(start)):
            return (str(instead) + reply[len(start) :]).rstrip(".!")
    return reply.rstrip(".!")


def proposed(
    lang: Language, outcome: Outcome, replies: Sequence[str] = (), after: Sequence[str] = ()
) -> Outcome:
    """The confirmation question of a reading that lacks evidence, with the reading to act on: each
    intent said back (`replies`, one per step; the outcome's own reply when it has one step), then
    what the reply says besides (`after`: "I can't inspect it myself.")."""
    said = list(replies) or [outcome.reply]
    action = action_said(lang, said[0])
    for reply in said[1:]:
        action = say(lang, "confirm.then", action=action, next=action_said(lang, reply))
    question = " ".join([say(lang, "confirm.question", action=action), *after])
    steps = [replace(o, unsure=False, more=()) for o in outcome.steps()]
    proposal = replace(steps[0], more=tuple(steps[1:]))
    return Outcome(question, confidence=outcome.confidence, clarify=True, proposal=proposal,
                   guessed=outcome.guesses)  # fmt: skip


def answered(reader: Reader, answer: list[str]) -> Outcome | None:
    """What the words (`answer`, its ways of saying no said "no") make of the reading the robot
    proposed in its last question: "yes" the reading, "no" nothing done; None when the last
    question proposed nothing, or proposed something this conversation no longer reads so, or the
    words neither accept nor refuse it."""
    lang = reader.lexicon.lang
    said = [w for w in answer if w != "no"]
    refused = answer[:1] == ["no"] and set(said) <= lang.followups.accepting
    if not refused and (answer[:1] == ["no"] or not accepts(lang, said)):
        return None
    spoken = [i for i, u in enumerate(reader.history) if u.role != "system"]
    if len(spoken) < 2:
        return None
    question, request = reader.history[spoken[-1]], reader.history[spoken[-2]]
    if question.role != "assistant" or request.role != "user":
        return None
    again = reader.within(reader.history[: spoken[-2]]).interpret(request.text)
    if again.proposal is None or again.reply != question.text.strip():
        return None
    if refused:
        return Outcome(say(lang, "confirm.dropped"))
    steps = [replace(o, confidence=min(o.confidence, CONFIRMED_CONFIDENCE), more=())
             for o in again.proposal.steps()]  # fmt: skip
    return replace(steps[0], more=tuple(steps[1:]))
