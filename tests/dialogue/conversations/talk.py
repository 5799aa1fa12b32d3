"""A conversation through the engine, turn by turn, as a person has it: what each reply says and
which intents it carries (the transcript tests of issue 30's classes)."""

from __future__ import annotations

import asyncio
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
