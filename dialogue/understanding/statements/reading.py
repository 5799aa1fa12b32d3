"""The rules' reading of a turn about what people know: statements told, or questions about them.

Tried before the command grammar (dialogue.llm.rules): a turn that is not one is left to it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.reference.lexicon import Lexicon
from dialogue.schema import ChatbotResponse, UserIntent
from dialogue.understanding.followups.statement import follow_up
from dialogue.understanding.questions.told import Asking
from dialogue.understanding.replies import say
from dialogue.understanding.statements.grammar import Statements


@dataclass(frozen=True)
class Reading:
    answer: ChatbotResponse
    #: The answer asks which referent was meant.
    clarify: bool = False


def read_turn(text: str, lexicon: Lexicon, speaker: str, history: Sequence[Utterance] = ()) -> Reading | None:
    """The answer (facts, a greeting that came with them, or the reply saying why nothing could be
    learnt), or None when the turn neither tells nor asks what people know."""
    asked = Asking(lexicon, speaker, history).read(text)
    if asked is not None:
        return Reading(ChatbotResponse(facts=asked))
    told = follow_up(text, lexicon, speaker, history) or Statements(lexicon, speaker, history).read(text)
    if told is None:
        return None
    if told.reply is not None:
        return Reading(ChatbotResponse(verbal_ack=told.reply), clarify=told.clarify)
    greet = UserIntent(type=I.GREET, recipient=speaker, confidence=0.9) if told.greeted else None
    hello = say(lexicon.lang, "social.hello") if greet else None
    return Reading(ChatbotResponse(verbal_ack=hello, user_intent=greet, facts=told.facts))
