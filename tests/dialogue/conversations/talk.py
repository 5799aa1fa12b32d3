"""A conversation through the engine, turn by turn, as a person has it: what each reply says and
which intents it carries (the transcript tests of issue 30's classes)."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

from dialogue.engine import DialogueEngine
from dialogue.sessions.manager import DialogueManager
from kb import KB


@dataclass(frozen=True)
class Said:
    reply: str
    intents: tuple[tuple[str, dict[str, object]], ...]


class Talk:
    """One dialogue with the rules engine over a KB made of `statements`."""

    def __init__(self, statements: list[str], speaker: str) -> None:
        self.kb = KB()
        self.kb.update(statements)
        self.manager = DialogueManager(DialogueEngine(self.kb))
        self.dialogue = self.manager.start().id
        self.speaker = speaker

    def __call__(self, text: str) -> Said:
        result = asyncio.run(self.manager.interact(self.speaker, text, dialogue_id=self.dialogue))
        return Said(result.response, tuple((i.intent, dict(i.data)) for i in result.intents))

    def close(self) -> None:
        self.kb.close()


@contextmanager
def talking(statements: list[str], speaker: str) -> Iterator[Talk]:
    """A `Talk`, closed after (what each module's `talk` fixture yields)."""
    talk = Talk(statements, speaker)
    try:
        yield talk
    finally:
        talk.close()


# --- a scene's statements, one call per entity ------------------------------------------------------

def robot() -> list[str]:
    return ["myself rdf:type Robot"]


def zone(term: str, label: str) -> list[str]:
    return [f"{term} rdf:type ZoneOfInterest", f'{term} rdfs:label "{label}"']


def person(term: str, name: str, *, zone: str | None = None, seen: bool = False) -> list[str]:
    """A person the KB knows by name; in a zone, seen by the robot if said so."""
    return [f"{term} rdf:type Human", f'{term} rdfs:label "{name}"', *_placed(term, zone, None, None, seen)]


def thing(term: str, kind: str, label: str, *, zone: str | None = None, on: str | None = None,
          color: str | None = None, owner: str | None = None, seen: bool = False) -> list[str]:
    """A thing of class `kind` called `label`; where it is, its colour, whose it is, if said so."""
    return [f"{term} rdf:type {kind}", f'{term} rdfs:label "{label}"', *_placed(term, zone, on, color, seen, owner)]


def _placed(term: str, zone: str | None, on: str | None, color: str | None, seen: bool,
            owner: str | None = None) -> list[str]:
    facts = {"hasColor": color, "belongsTo": owner, "isOn": on, "isIn": zone}
    return [*(f"{term} {p} {o}" for p, o in facts.items() if o is not None), *([f"myself sees {term}"] * seen)]
