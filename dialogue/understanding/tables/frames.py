"""The model of `frames.toml`: the verb frames of requests."""

from __future__ import annotations

from typing import Literal

from pydantic import ConfigDict

from dialogue.understanding.tables.base import (
    Phrase,
    Table,
)


class FrameRow(Table):
    """`frames.toml` [[frame]]: one verb frame, as the file says it (dialogue.understanding.requests.frames
    reads it into a `Frame`)."""

    model_config = ConfigDict(frozen=True, extra="forbid", alias_generator=lambda n: n.replace("_", "-"))

    verbs: str
    intent: str | None = None
    direct: str | None = None
    slots: dict[str, str] = {}
    particles: str = ""
    here: str | None = None
    there_only: bool = False
    here_only: bool = False
    dative: Literal["me", "any", "before"] | None = None
    only: str | None = None
    requires: tuple[str, ...] = ()
    defaults: dict[str, Phrase] = {}
    whole: bool = False
    text: Literal["verb", "activity", "doing", "stopping"] | None = None
    named: str | None = None
    special: str | None = None
    serial: bool = False


class FrameTable(Table):
    """`frames.toml`: the verb frames, their groups of words, the constructions tried before them."""

    constructions: tuple[str, ...] = ()
    groups: dict[str, str] = {}
    frame: tuple[FrameRow, ...] = ()

    def group_words(self, name: str) -> frozenset[str]:
        """The words of a group of single words ("out over back"), none for a group it lacks."""
        return frozenset(self.groups.get(name, "").split())
