"""Each person's memory across dialogues, kept in the KB: when they last spoke, and a short summary.

    person_bob lastSpokeAt "2025-06-01T10:30:00+00:00"^^xsd:dateTime
    person_bob dialogueSummary "2025-06-01: said \"the red mug is mine\"; asked \"bring me the cup\""

Both are functional properties of the robot's model, so they survive a restart with the journal and
are shared with read replicas through the store, like any fact. The summary keeps the person's last
few notable turns (what they told, what they asked the robot to do), newest last, bounded in notes
and characters: chatbot_msgs 4.0's `summary` of earlier sessions. A turn with nothing notable only
moves `lastSpokeAt`, written at most once per `refresh` seconds per person, so chit-chat does not
write to the KB on every turn.
"""

from __future__ import annotations

import asyncio
import logging
import threading
from collections import OrderedDict
from dataclasses import dataclass
from datetime import UTC, datetime
from typing import Any

from rdflib import XSD, Literal, URIRef

from dialogue import intents as I
from dialogue.memory.provenance import Told, told
from dialogue.observers import TurnRecord
from dialogue.speakers import person_statement
from kb import KbError
from kb.protocol import KnowledgeBase
from kb.terms import ORO, format_term, format_triple, parse_name

log = logging.getLogger(__name__)

LAST_SPOKE = URIRef(ORO + "lastSpokeAt")
SUMMARY = URIRef(ORO + "dialogueSummary")
#: Notes kept in a summary, and its length.
MAX_NOTES = 6
MAX_SUMMARY = 600
#: Characters of an utterance kept in its note.
MAX_QUOTE = 80
#: People whose last write time is remembered in this process (the least recently seen forgotten).
MAX_TRACKED = 10_000
_SEPARATOR = "; "


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
    acted = [i for i in result.intents if i.intent != I.RAW_USER_INPUT]
    told = [c for c in result.claims if not c.asks]
    if not acted and not told:
        return None
    quote = " ".join(record.text.split())
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
        self._written: OrderedDict[str, float] = OrderedDict()
        self._lock = threading.Lock()

    def recall(self, person: str) -> Recollection:
        term = self._term(person)
        if term is None:
            return Recollection(person)
        s = format_term(term)
        spoke = self.kb.find([f"{s} {format_term(LAST_SPOKE)} ?t"])
        summary = self.kb.find([f"{s} {format_term(SUMMARY)} ?s"])
        return Recollection(person, str(spoke[0]["t"]) if spoke else None,
                            str(summary[0]["s"]) if summary else "")

    def remember(self, record: TurnRecord) -> bool:
        """Note the turn in its speaker's memory; True when the KB was written (blocking)."""
        due = self._due(record)
        if due is None:
            return False
        self._write(record, *due)
        return True

    def _due(self, record: TurnRecord) -> tuple[URIRef, str | None] | None:
        """The speaker's term and the turn's note when the KB is to be written, else None (cheap:
        no KB access). A turn the service could not answer (its fallback: model or store down)
        writes nothing more to a KB that may be struggling."""
        term = self._term(record.user_id)
        if term is None or record.result.error_msg:
            return None
        added = note(record)
        with self._lock:
            last = self._written.get(record.user_id)
            if added is None and last is not None and record.at - last < self.refresh:
                return None
            self._written[record.user_id] = record.at
            self._written.move_to_end(record.user_id)
            while len(self._written) > MAX_TRACKED:
                self._written.popitem(last=False)
        return term, added

    def _write(self, record: TurnRecord, term: URIRef, added: str | None) -> None:
        stamp = Literal(datetime.fromtimestamp(record.at, UTC).isoformat(timespec="seconds"),
                        datatype=XSD.dateTime)
        facts = [format_triple((term, LAST_SPOKE, stamp))]
        if added is not None:
            summary = summarised(self.recall(record.user_id).summary, added)
            facts.append(format_triple((term, SUMMARY, Literal(summary))))
        self.kb.update(facts)  # functional properties: the new values replace the old

    def about(self, person: str) -> dict[str, Any]:
        """Everything the robot keeps of a person: when they last spoke, the summary, the facts
        they told it (adopted: those they only believe are in their own model) and the facts others
        told about them, each with who told it and when."""
        memory = self.recall(person)
        if self._term(person) is None:
            return {"person": person, "last_spoke": None, "summary": "", "told": [], "told_about": []}
        return {"person": person, "last_spoke": memory.last_spoke, "summary": memory.summary,
                "told": [_told(t) for t in told(self.kb, by=person)],
                "told_about": [_told(t) for t in told(self.kb, subject=person)]}

    def recall_note(self, person: str) -> str | None:
        return self.recall(person).note()

    async def observe(self, record: TurnRecord) -> None:
        """The dialogue manager's observer: off the event loop only when there is something to write."""
        due = self._due(record)
        if due is None:
            return
        try:
            await asyncio.to_thread(self._write, record, *due)
        except KbError as exc:
            log.warning("the memory of %s was not kept for this turn: %s", record.user_id, exc)

    @staticmethod
    def _term(person: str) -> URIRef | None:
        """The person's KB term, or None for who is nobody to remember (source constants...)."""
        if person_statement(person) is None:
            return None
        return parse_name(person, "person")


def _told(fact: Told) -> dict[str, Any]:
    return {"subject": fact.subject, "predicate": fact.predicate, "object": fact.object, "by": fact.by,
            "at": fact.at, "words": fact.words}
