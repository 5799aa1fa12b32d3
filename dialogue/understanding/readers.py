"""The readers of a turn, one per kind of utterance, tried in order: their order is data (`READERS`).

Each reader says what it reads and returns what it heard, or None when the turn is not its kind
(the next one is then tried). The readers of the default role, in order:

    told questions     questions about what people told ("what does Alice like?")
    statement answers  an answer to the robot's question about a statement ("the red one")
    statements         what people tell ("I'm Bob", "the keys are in the drawer", "I like tea")
    requests           the interpreter (dialogue.understanding.interpret), which reads each act of
                       the grammar by its row of `ACTS`: social talk, questions about the situation
                       (dialogue.understanding.questions.situation, by kind: `QUESTIONS`) and
                       requests; and an utterance with no act by the follow-ups in their order
                       (dialogue.understanding.followups.request `FOLLOW_UPS`): an answer to the
                       robot's question about a request, a correction, the same request again

Every reader reads the same `Said` (dialogue.understanding.said): the turn's words, tokenised and
normalised once. The ask role reads an answer to its form with its own reader,
dialogue.understanding.followups.form (`read_answer`: each clause to one field). What the rules
answer goes through the same validation as a model's answer.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.reference.lexicon import Lexicon
from dialogue.schema import FREE_FORM_OBJECT, ChatbotResponse, UserIntent
from dialogue.understanding.followups.statement import follow_up
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.questions.told import Asking
from dialogue.understanding.replies import say
from dialogue.understanding.said import Said
from dialogue.understanding.statements.clause import Told
from dialogue.understanding.statements.grammar import Statements


@dataclass(frozen=True)
class Turn:
    """What the readers read: the words said (read once, dialogue.understanding.said), by whom,
    after what, against which KB names."""

    said: Said
    lexicon: Lexicon
    speaker: str
    history: tuple[Utterance, ...] = ()
    robot_name: str = "robot"


@dataclass(frozen=True)
class Heard:
    """What a reader made of a turn: the answer, in the answer schema, and how sure of it."""

    answer: ChatbotResponse
    #: The answer asks which referent was meant.
    clarify: bool = False
    #: The turn was understood (else the rules claim nothing of it).
    understood: bool = True
    #: A referent was read from a misheard or mistyped name ("the thremos"): a guess.
    guessed: bool = False
    #: What people know (facts and what the robot says of them), rather than intents.
    told: bool = False
    #: The interpreter's reading of a request, when the requests' reader heard it.
    outcome: Outcome | None = None
    #: The answer proposes a reading the rules lack evidence for ("Shall I...?"), acting on none.
    proposes: bool = False
    #: The person took leave: the conversation ends with this answer.
    ends: bool = False


@dataclass(frozen=True)
class Reader:
    """One kind of utterance: what it reads, and how."""

    name: str
    reads: str
    read: Callable[[Turn], Heard | None]


def _told(turn: Turn, told: Told | None) -> Heard | None:
    """What a statement (or the answer that completes one) says: its facts, or why none."""
    if told is None:
        return None
    if told.reply is not None:
        return Heard(ChatbotResponse(verbal_ack=told.reply), clarify=told.clarify, told=True)
    greet = UserIntent(type=I.GREET, recipient=turn.speaker, confidence=0.9) if told.greeted else None
    hello = say(turn.lexicon.lang, "social.hello") if greet else None
    return Heard(ChatbotResponse(verbal_ack=hello, user_intent=greet, facts=told.facts), told=True)


def _told_questions(turn: Turn) -> Heard | None:
    asked = Asking(turn.lexicon, turn.speaker, turn.history).read(turn.said)
    return Heard(ChatbotResponse(facts=asked), told=True) if asked is not None else None


def _statement_answers(turn: Turn) -> Heard | None:
    return _told(turn, follow_up(turn.said, turn.lexicon, turn.speaker, turn.history))


def _statements(turn: Turn) -> Heard | None:
    return _told(turn, Statements(turn.lexicon, turn.speaker, turn.history).read(turn.said))


def _wish(outcome: Outcome) -> UserIntent:
    roles = dict(outcome.roles)
    free = roles.pop("object", None) if outcome.intent in FREE_FORM_OBJECT else None
    return UserIntent(type=outcome.intent, input=free, confidence=outcome.confidence, **roles)


def answer_of(outcome: Outcome) -> ChatbotResponse:
    """The interpreter's outcome in the answer schema: the reply and its intents, in order."""
    steps = [o for o in outcome.steps() if o.intent is not None]
    if not steps:
        return ChatbotResponse(verbal_ack=outcome.reply, user_intent=None)
    wishes = [_wish(o) for o in steps]
    return ChatbotResponse(
        verbal_ack=outcome.reply, user_intent=wishes[0], user_intents=wishes if len(wishes) > 1 else None
    )


def interpreted(turn: Turn) -> Outcome:
    """The interpreter's reading of the turn (dialogue.understanding.interpret)."""
    return Interpreter(turn.lexicon, turn.speaker, turn.history, turn.robot_name).interpret(turn.said)


def _requests(turn: Turn) -> Heard:
    outcome = interpreted(turn)
    return Heard(answer_of(outcome), clarify=outcome.clarify, understood=outcome.understood,
                 guessed=outcome.guesses, outcome=outcome, proposes=outcome.proposal is not None,
                 ends=outcome.farewell)  # fmt: skip


#: The readers of the default role, in the order they are tried: the first that hears the turn
#: answers it.
READERS: tuple[Reader, ...] = (
    Reader("told questions", "questions about what people told: 'what does Alice like?'", _told_questions),
    Reader("statement answers", "an answer to the robot's question about a statement: 'the red one'",
           _statement_answers),
    Reader("statements", "what people tell: 'I'm Bob', 'the keys are in the drawer', 'I like tea'",
           _statements),
    Reader("requests", "requests, questions about the situation, social talk, and answers to the robot's "
           "question about a request", _requests),
)  # fmt: skip


def read(turn: Turn, readers: Sequence[Reader] = READERS) -> Heard:
    """What the first reader that hears the turn made of it (the requests' reader always answers:
    when nothing was understood, it says so)."""
    for reader in readers:
        heard = reader.read(turn)
        if heard is not None:
            return heard
    not_understood = say(turn.lexicon.lang, "sorry.not_understood")
    return Heard(ChatbotResponse(verbal_ack=not_understood, user_intent=None), understood=False)
