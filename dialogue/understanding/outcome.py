"""What the rules make of an utterance: a reply, maybe intents (in order), and how sure they are."""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from dialogue.reference.english import Words
from dialogue.reference.grounding import Entity

#: How sure the rules are of a turn in which they corrected a slip ("plase", "thremos").
SPELT_CONFIDENCE = 0.7


@dataclass(frozen=True)
class Outcome:
    reply: str
    intent: str | None = None
    roles: dict[str, str] = field(default_factory=dict)
    confidence: float = 0.9
    understood: bool = True
    clarify: bool = False
    #: For a follow-up turn: the role whose phrase was ambiguous (or missing), and that phrase.
    open_role: str | None = None
    open_phrase: Words = ()
    #: The intents that follow this one in a compound request, in order.
    more: tuple[Outcome, ...] = ()
    #: A misspelt word was read as a name the KB has ("the thremos"): which thing is meant is a
    #: guess (dialogue.understanding.speech.spelling), which a hybrid model leaves to its model.
    guessed: bool = False
    #: The reading lacks evidence (a word it cannot account for, a frame that only half fits): it is
    #: not acted on but proposed (`proposed`).
    unsure: bool = False
    #: A confirmation question ("Shall I bring Jordan the soap?"): the reading it proposes, acted on
    #: when the speaker says yes (dialogue.understanding.followups.proposal).
    proposal: Outcome | None = None
    #: The person took leave ("bye"): the conversation ends with this reply.
    farewell: bool = False

    def steps(self) -> tuple[Outcome, ...]:
        """This outcome and the ones that follow it."""
        return (self, *self.more)

    def followed_up(self) -> Outcome:
        """The outcome as a follow-up completes it: a little less sure than a request said whole,
        and without the steps that followed it."""
        return replace(self, confidence=0.8, more=())

    @property
    def guesses(self) -> bool:
        """Whether this outcome or one that follows it is a guess."""
        return any(o.guessed for o in self.steps())

    @property
    def doubts(self) -> bool:
        """Whether this outcome or one that follows it lacks evidence."""
        return any(o.unsure for o in self.steps())


@dataclass(frozen=True)
class Ref:
    """What a noun phrase grounded to: one entity, the speaker, or the outcome that says why not."""

    entity: Entity | None = None
    speaker: bool = False
    #: The entity was read from a misheard or mistyped name ("bay mine"): a guess.
    guessed: bool = False
    problem: Outcome | None = None
