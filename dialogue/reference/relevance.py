"""Which entities a turn's prompt and schema show when there are more than they can hold.

The snapshot holds every entity (the rules and the validation of answers use them all); the
prompt's share is chosen per turn by relevance, not by id: the speaker and the people present
first, then what the utterance names (what the robot sees of it first), what the robot sees
(things where the speaker or the robot is first), the supports and zones of what is kept, then
the rest in the snapshot's order. Each step reads only the bounded parts of the snapshot (people,
visible things, mentioned ones), so the cost does not grow with the KB.
"""

from __future__ import annotations

import heapq
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import overload

from dialogue.reference.lexicon import Lexicon
from dialogue.reference.snapshot import Entity, Snapshot


def mentioned(lexicon: Lexicon, words: Sequence[str]) -> list[str]:
    """Ids of the entities the utterance's words (its tokens) name, in no particular order:
    `ranked` orders them (a class word may name thousands; sorting them all is wasted)."""
    return [e for m in lexicon.mentions(list(words)) for e in m.entities]


def ranked(snapshot: Snapshot, speaker: str, limit: int, mentions: Iterable[str] = ()) -> list[Entity]:
    """At most `limit` entities, most relevant first (deterministic)."""
    kept: dict[str, Entity] = {}

    def add(entities: Iterable[Entity | None]) -> bool:
        """Keep these in turn; False once the share is full."""
        for entity in entities:
            if len(kept) >= limit:
                return False
            if entity is not None:
                kept.setdefault(entity.id, entity)
        return len(kept) < limit

    speaking, robot = snapshot.get(speaker), snapshot.get(snapshot.robot)
    people = snapshot.of_kind("person")
    here = {p for who in (speaking, robot) if who is not None for p in (who.zone, who.support) if p}

    def near(entity: Entity) -> tuple[bool, tuple[int, str]]:
        return (entity.zone not in here and entity.support not in here, snapshot.order_key(entity.id))

    visible = sorted(snapshot.visible(), key=near)
    # A class word ("apple") may name thousands: the visible ones first, then the first by id
    # (heapq on the ids: no per-entity work for the ones that do not make the share).
    names = dict.fromkeys(mentions)
    shown = [e for e in visible if e.id in names]
    named = [*shown, *map(snapshot.get, heapq.nsmallest(limit, names.keys() - {e.id for e in shown}))]
    present = (e for e in people if e.seen)
    steps: tuple[Iterable[Entity | None], ...] = ((speaking, robot), present, named, visible)
    if not all(add(step) for step in steps):
        return list(kept.values())
    places = [p for e in list(kept.values()) for p in (e.support, e.zone) if p]
    if add(map(snapshot.get, places)):
        add(snapshot.entities.values())  # lazily, in order: stops once the share is full
    return list(kept.values())


class Focus(Sequence[Entity]):
    """`ranked`, worked out when first read: a turn the rules answer builds no prompt and no schema,
    and ranks nothing (a third of a rules turn went to a ranking nobody read). ``then`` is told
    the ranking once it is made (the turn's trace)."""

    __slots__ = ("_limit", "_mentions", "_ranked", "_snapshot", "_speaker", "_then")

    def __init__(self, snapshot: Snapshot, speaker: str, limit: int, mentions: Callable[[], Iterable[str]],
                 then: Callable[[Sequence[Entity]], object] | None = None) -> None:
        self._snapshot, self._speaker, self._limit = snapshot, speaker, limit
        self._mentions, self._then = mentions, then
        self._ranked: tuple[Entity, ...] | None = None

    @property
    def entities(self) -> tuple[Entity, ...]:
        if self._ranked is None:
            self._ranked = tuple(ranked(self._snapshot, self._speaker, self._limit, self._mentions()))
            if self._then is not None:
                self._then(self._ranked)
        return self._ranked

    @overload
    def __getitem__(self, index: int) -> Entity: ...

    @overload
    def __getitem__(self, index: slice) -> Sequence[Entity]: ...

    def __getitem__(self, index: int | slice) -> Entity | Sequence[Entity]:
        return self.entities[index]

    def __len__(self) -> int:
        return len(self.entities)

    def __iter__(self) -> Iterator[Entity]:
        return iter(self.entities)
