"""The robot's initiative: when a person becomes engaged, reach out to them.

Engagement comes from the KB, whoever writes it: the scene's engagement state machine (scene.world)
or any producer's `<person> engagementLevel engaged`. On each transition into `engaged` (the fact
added to the robot's model), as hri_engagement does, the robot emits `__intent_engage_with__` with
that person as recipient (source `__myself__`, modality motion: the person's approach and gaze);
and, when greeting is on, greets them: a `__intent_greet__` and what it says, by name when it knows
one ("Hello Bob!", "Hello Bob, nice to see you again!" when they spoke before; "Hello!" to a person
it has never met). A person is greeted at most once per `interval` seconds: one who leaves and comes
back within it gets the engage intent but no second greeting; after it, a greeting again.

The KB calls the commit listener under its lock, so it only queues the person; a worker thread reads
the names and publishes. A service that sees no commits (a read replica) has no initiative: the
writer, which every write goes through, has it.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

from rdflib import URIRef

from dialogue import intents as I
from dialogue.follower import CommitFollower
from dialogue.pushed.bus import IntentBus
from dialogue.understanding.language import Language
from dialogue.understanding.replies import say
from kb.protocol import KnowledgeBase
from kb.terms import ORO, format_term, parse_name, shorten

ENGAGEMENT = URIRef(ORO + "engagementLevel")
ENGAGED = URIRef(ORO + "engaged")
#: People queued between the KB's commits and the worker (past it, a burst drops the newest).
MAX_PENDING = 1000
#: Greeting times kept before those older than the interval are forgotten.
MAX_REMEMBERED = 10_000


@dataclass(frozen=True)
class InitiativeConfig:
    #: Greet a person who becomes engaged.
    greet: bool = True
    #: Seconds before the same person is greeted again.
    interval: float = 300.0


class Initiative(CommitFollower[str]):
    """Watches a KB's commits for people becoming engaged (not on a read replica); engages and
    greets them on a bus. `join` waits until every engagement queued so far was reached out to."""

    def __init__(self, kb: KnowledgeBase, bus: IntentBus, config: InitiativeConfig | None = None,
                 clock: Callable[[], float] = time.monotonic, language: Language | None = None) -> None:
        super().__init__(kb, "initiative", _engaged, self.engaged, MAX_PENDING)
        self.bus = bus
        #: The language of the greetings (`replies.toml` [social]), as the engine's.
        self.language = language or Language.load()
        self.config = config or InitiativeConfig()
        self.clock = clock
        self._greeted: dict[str, float] = {}

    def engaged(self, person: str) -> None:
        """Reach out to a person who just became engaged (blocking: reads the KB for the name)."""
        data: dict[str, str | None] = {"recipient": person}
        self.bus.publish("initiative", I.make_intent(I.ENGAGE_WITH, data, source=I.ROBOT_ITSELF,
                                                     confidence=1.0, modality=I.MODALITY_MOTION))
        if not self.config.greet:
            return
        now = self.clock()
        last = self._greeted.get(person)
        if last is not None and now - last < self.config.interval:
            return
        words = self.greeting(person)
        self._greeted[person] = now
        if len(self._greeted) > MAX_REMEMBERED:  # only those within the interval matter
            self._greeted = {p: t for p, t in self._greeted.items() if now - t < self.config.interval}
        greet = I.make_intent(I.GREET, data, source=I.ROBOT_ITSELF, confidence=1.0,
                              modality=I.MODALITY_INTERNAL)
        self.bus.publish("initiative", greet, response=words)

    def greeting(self, person: str) -> str:
        term = format_term(parse_name(person, "person"))
        names = sorted(str(r["l"]) for r in self.kb.find([f"{term} rdfs:label ?l"]))
        if not names:
            return say(self.language, "social.hello")
        if self.kb.exist([f"{term} lastSpokeAt ?t"]):
            return say(self.language, "social.hello_again", name=names[0])
        return say(self.language, "social.hello_you", name=names[0])


def _engaged(commit: Any) -> Iterator[str]:
    """Who became engaged in a commit (called by the KB under its lock: no KB access)."""
    for delta in commit.deltas:
        if delta.model != "default":
            continue
        for s, p, o in delta.added:
            if p == ENGAGEMENT and o == ENGAGED and isinstance(s, URIRef):
                yield str(shorten(s))
