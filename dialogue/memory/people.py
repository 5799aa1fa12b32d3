"""Each person's memory across dialogues, kept in the KB: when they last spoke, and a short summary.

    person_bob lastSpokeAt "2025-06-01T10:30:00+00:00"^^xsd:dateTime
    person_bob dialogueSummary "2025-06-01: said \"the red mug is mine\"; asked \"bring me the cup\""

Both are functional properties of the robot's model, so they survive a restart with the journal and
are shared with read replicas through the store, like any fact. The summary keeps the person's last
few notable turns (what they told, what they asked the robot to do), newest last, bounded in notes
and characters: chatbot_msgs 4.0's `summary` of earlier sessions. A turn that told something writes
them at once (it wrote what it told anyway); other turns write at most once per `refresh` seconds
per person, their notes waiting in memory for the next write (so a crash loses at most that much; a
clean stop writes them), and neither requests nor chit-chat write to the KB on every turn.
"""

from __future__ import annotations

import asyncio
import logging
import threading
from collections import OrderedDict
from dataclasses import asdict, dataclass
from datetime import UTC, datetime
from functools import lru_cache
from typing import Any

from rdflib import XSD, Literal, URIRef

from dialogue import intents as I
from dialogue.memory.provenance import Told, told
from dialogue.memory.recollections import LAST_SPOKE, SUMMARY, Recollections
from dialogue.sessions.observers import TurnRecord
from dialogue.speakers import NOT_PEOPLE, NotAPerson, check_speaker, person_statement
from kb import KbError
from kb.protocol import KnowledgeBase
from kb.terms import format_term, format_triple, parse_name
from kb.unicode import carried_line

log = logging.getLogger(__name__)

#: Notes kept in a summary, and its length.
MAX_NOTES = 6
MAX_SUMMARY = 600
#: Characters of an utterance kept in its note.
MAX_QUOTE = 80
#: People whose last write time is remembered in this process (the least recently seen forgotten).
MAX_TRACKED = 10_000
_SEPARATOR = "; "
#: Intents that ask the robot to do nothing worth remembering: a turn not understood, a greeting.
_NO_REQUEST = frozenset({I.RAW_USER_INPUT, I.GREET})


@dataclass(frozen=True)
class _Kept:
    """What is kept of a person between writes: when the KB was last written, and the notes and
    time of the turns since, which wait for the next write."""

    written: float
    notes: tuple[str, ...] = ()
    spoke: float | None = None


@dataclass(frozen=True)
class Recollection:
    person: str
    last_spoke: str | None = None
    summary: str = ""

    def note(self) -> str | None:
        """What a model is told of earlier dialogues with the person (a system note), if anything."""
        if self.last_spoke is None:
            return None
        when = self.last_spoke.replace("T", " at ")[:19]  # to the minute
        earlier = f" Earlier: {self.summary}." if self.summary else ""
        return f"You last spoke with [{self.person}] on {when} UTC.{earlier}"


def note(record: TurnRecord) -> str | None:
    """A turn's note for the summary, or None when nothing in it is worth remembering."""
    result = record.result
    acted = [i for i in result.intents if i.intent not in _NO_REQUEST]
    told = [c for c in result.claims if not c.asks]
    if not acted and not told:
        return None
    quote = carried_line(record.text)
    quote = quote if len(quote) <= MAX_QUOTE else quote[: MAX_QUOTE - 1] + "…"
    day = datetime.fromtimestamp(record.at, UTC).date().isoformat()
    return f'{day}: {"said" if told and not acted else "asked"} "{quote}"'


def summarised(previous: str, added: str) -> str:
    """The summary with one more note, the oldest dropped past the bounds."""
    notes = [n for n in previous.split(_SEPARATOR) if n] + [added]
    notes = notes[-MAX_NOTES:]
    while len(notes) > 1 and len(_SEPARATOR.join(notes)) > MAX_SUMMARY:
        notes.pop(0)
    return _SEPARATOR.join(notes)[:MAX_SUMMARY]


class People:
    """Reads and keeps each person's memory in a KB (blocking calls; `observe` is the async
    observer of the dialogue manager, which runs them off the event loop)."""

    def __init__(self, kb: KnowledgeBase, refresh: float = 60.0) -> None:
        self.kb = kb
        self.refresh = refresh
        #: Per person: when the KB was last written, and what waits for the next write.
        self._written: OrderedDict[str, _Kept] = OrderedDict()
        self._lock = threading.Lock()
        self._index: Recollections | None = None

    def follow(self) -> None:
        """Keep an index of everyone's memory from the KB's commits from now on (when the KB
        reports them: not a read replica), so that recalling costs no KB query. Call it once the KB
        holds what it starts with (recovered from the journal), blocking."""
        self._index = Recollections.follow(self.kb)

    def close(self) -> None:
        """Write what waits for the next write (a clean stop loses nothing), stop the index."""
        try:
            self.flush()
        except KbError as exc:
            log.warning("the memory of the last turns was not kept at stop: %s", exc)
        if self._index is not None:
            self._index.close()

    def flush(self) -> None:
        """Write every person's turns that wait for their next write (blocking)."""
        with self._lock:
            waiting = [(person, kept) for person, kept in self._written.items() if kept.spoke is not None]
            for person, kept in waiting:
                self._written[person] = _Kept(kept.spoke or kept.written)
        for person, kept in waiting:
            term = self._term(person)
            if term is not None and kept.spoke is not None:
                self._write(person, term, kept.spoke, kept.notes)

    def recall(self, person: str) -> Recollection:
        """Blocking unless the index answers."""
        term = self._term(person)
        if term is None:
            return Recollection(person)
        if self._index is not None:
            return Recollection(person, *self._index.get(person))
        s = format_term(term)
        spoke = self.kb.find([f"{s} {format_term(LAST_SPOKE)} ?t"])
        summary = self.kb.find([f"{s} {format_term(SUMMARY)} ?s"])
        return Recollection(person, str(spoke[0]["t"]) if spoke else None,
                            str(summary[0]["s"]) if summary else "")

    async def recall_note(self, person: str) -> str | None:
        """What a model is told of earlier dialogues with the person: from the index on the event
        loop, else from the KB off it."""
        if self._index is not None:
            return self.recall(person).note()
        return (await asyncio.to_thread(self.recall, person)).note()

    def remember(self, record: TurnRecord) -> bool:
        """Note the turn in its speaker's memory; True when the KB was written (blocking)."""
        due = self._due(record)
        if due is None:
            return False
        self._write(record.user_id, *due)
        return True

    def _due(self, record: TurnRecord) -> tuple[URIRef, float, tuple[str, ...]] | None:
        """The speaker's term, the time and the notes to write when the KB is to be written now, else None
        (cheap: no KB access). A turn the service could not answer (its fallback: model or store
        down) writes nothing more to a KB that may be struggling."""
        term = self._term(record.user_id)
        if term is None or record.result.error_msg:
            return None
        added = note(record)
        told_something = any(not c.asks for c in record.result.claims)
        with self._lock:
            kept = self._written.get(record.user_id)
            waiting = kept.notes if kept is not None else ()
            notes = (*waiting, added)[-MAX_NOTES:] if added is not None else waiting
            due = told_something or kept is None or record.at - kept.written >= self.refresh
            self._written[record.user_id] = (_Kept(record.at) if due or kept is None
                                             else _Kept(kept.written, notes, record.at))
            self._written.move_to_end(record.user_id)
            while len(self._written) > MAX_TRACKED:
                self._written.popitem(last=False)
        return (term, record.at, notes) if due else None

    def _write(self, person: str, term: URIRef, at: float, notes: tuple[str, ...]) -> None:
        stamp = Literal(datetime.fromtimestamp(at, UTC).isoformat(timespec="seconds"), datatype=XSD.dateTime)
        facts = [format_triple((term, LAST_SPOKE, stamp))]
        if notes:
            summary = self.recall(person).summary
            for added in notes:
                summary = summarised(summary, added)
            facts.append(format_triple((term, SUMMARY, Literal(summary))))
        self.kb.update(facts)  # functional properties: the new values replace the old

    def about(self, person: str) -> dict[str, Any]:
        """Everything the robot keeps of a person: when they last spoke, the summary, the facts
        they told it (adopted: those they only believe are in their own model) and the facts others
        told about them, each with who told it and when. NotAPerson when `person` is no KB id, or
        names something of the KB that is no person."""
        if person not in NOT_PEOPLE and self._term(person) is None:
            raise NotAPerson(f"{person!r} is not a person's id (a KB name such as person_bob)")
        check_speaker(self.kb, person, "person")
        memory = self.recall(person)
        if self._term(person) is None:  # a source constant: nobody the robot remembers
            return {"person": person, "last_spoke": None, "summary": "", "told": [], "told_about": []}
        return {"person": person, "last_spoke": memory.last_spoke, "summary": memory.summary,
                "told": [_told(t) for t in told(self.kb, by=person)],
                "told_about": [_told(t) for t in told(self.kb, subject=person)]}

    async def observe(self, record: TurnRecord) -> None:
        """The dialogue manager's observer: off the event loop only when there is something to write."""
        due = self._due(record)
        if due is None:
            return
        try:
            await asyncio.to_thread(self._write, record.user_id, *due)
        except KbError as exc:
            log.warning("the memory of %s was not kept for this turn: %s", record.user_id, exc)

    @staticmethod
    def _term(person: str) -> URIRef | None:
        return _person_term(person)


def _told(fact: Told) -> dict[str, Any]:
    """A fact told as the people route shows it: its fields, less the record it is kept in."""
    shown = asdict(fact)
    del shown["record"]
    return shown


@lru_cache(maxsize=4096)
def _person_term(person: str) -> URIRef | None:
    """The person's KB term, or None for who is nobody to remember (source constants...)."""
    if person_statement(person) is None:
        return None
    return parse_name(person, "person")
