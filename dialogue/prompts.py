"""Prompt templates (files in the `prompts` package) and the chat messages of one turn.

Templates use `$placeholders` (string.Template). Rendering is strict both ways: a placeholder without
a value and a value without a placeholder are errors (D13). The static system prompt comes first,
the history next, and the per-turn situation with the user's words last, so that a local model's
prompt cache is reused across turns (D12: the snapshot replaces, never accumulates).
"""

from __future__ import annotations

import string
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from importlib import resources

from dialogue.errors import DialogueError
from dialogue.history import Utterance
from dialogue.intents import CATALOGUE, EXTRACTABLE
from dialogue.llm.base import ChatMessage, TurnContext
from dialogue.locales import is_english, language_name
from dialogue.schema import intent_keys, short_name
from dialogue.situation import describe

TEMPLATE_NAMES = ("system", "turn", "repair", "language")


class PromptError(DialogueError, ValueError):
    """A template cannot be rendered: missing or unexpected placeholder, unknown template."""


def load_template(name: str, package: str = "prompts") -> string.Template:
    try:
        text = resources.files(package).joinpath(f"{name}.txt").read_text(encoding="utf-8")
    except FileNotFoundError:
        raise PromptError(f"no prompt template {name!r} in package {package!r}") from None
    return string.Template(text)


def render(template: string.Template, values: Mapping[str, str]) -> str:
    expected = set(template.get_identifiers())
    given = set(values)
    if expected != given:
        missing, unused = sorted(expected - given), sorted(given - expected)
        raise PromptError(f"template placeholders do not match: missing {missing}, unused {unused}")
    try:
        return template.substitute(values)
    except (KeyError, ValueError) as exc:
        raise PromptError(f"cannot render template: {exc}") from None


def intent_list(intents: Sequence[str] = EXTRACTABLE) -> str:
    """One line per intent type: the short name a model writes (which says what it does) and its keys,
    required first, an optional one with "?"."""
    lines = []
    for value in intents:
        required = len([r for r in CATALOGUE[value].required if r != "other_data"])
        keys = [key if i < required else f"{key}?" for i, key in enumerate(intent_keys(value))]
        lines.append(f"- {short_name(value)}" + (f": {', '.join(keys)}" if keys else ""))
    return "\n".join(lines)


def history_message(utterance: Utterance) -> ChatMessage:
    if utterance.role == "user":
        return ChatMessage("user", f'{utterance.speaker} "{utterance.text}"')
    return ChatMessage(utterance.role, utterance.text)


#: System prompts a prompt set keeps rendered.
_SYSTEMS_KEPT = 16


@dataclass
class PromptSet:
    """The loaded templates; load once (e.g. per engine), render every turn."""

    system: string.Template
    turn: string.Template
    repair: string.Template
    #: Said after the turn when the dialogue is not in English (the situation stays in English).
    language: string.Template
    _systems: dict[tuple[str, tuple[str, ...]], str] = field(default_factory=dict, init=False, repr=False,
                                                             compare=False)

    @classmethod
    def load(cls, package: str = "prompts") -> PromptSet:
        return cls(*(load_template(name, package) for name in TEMPLATE_NAMES))

    def system_prompt(self, robot_name: str, intents: Sequence[str] = EXTRACTABLE) -> str:
        key = (robot_name, tuple(intents))
        said = self._systems.get(key)
        if said is None:  # the same every turn: rendered once (a few, kept)
            said = render(self.system, {"robot_name": robot_name, "intent_list": intent_list(intents)})
            if len(self._systems) >= _SYSTEMS_KEPT:
                self._systems.clear()
            self._systems[key] = said
        return said

    def messages(self, context: TurnContext, intents: Sequence[str] = EXTRACTABLE) -> tuple[ChatMessage, ...]:
        situation = describe(context.snapshot, context.speaker, context.focus).text
        turn = render(self.turn, {"situation": situation, "input": context.text})
        turn += self.language_line(context.locale)
        return (
            ChatMessage("system", self.system_prompt(context.robot_name, intents)),
            *(history_message(u) for u in context.history),
            ChatMessage("user", turn),
        )

    def language_line(self, locale: str | None) -> str:
        """The instruction to answer in the dialogue's language; nothing for English."""
        if is_english(locale) or locale is None:
            return ""
        return "\n\n" + render(self.language, {"language": language_name(locale)})

    def repair_message(self, errors: str) -> ChatMessage:
        return ChatMessage("user", render(self.repair, {"errors": errors}))
