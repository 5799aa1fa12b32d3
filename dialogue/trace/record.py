"""The trace of one dialogue turn, as data: what was sent to the model and why, and what came back.

The engine fills a `TraceRecorder` while the turn runs (each stage timed, each model request with its
messages, JSON schema, raw answer and validation error) and the turn's result carries the finished
`TurnTrace`, a pydantic model. It is bounded by construction: each text is cut at `MAX_TEXT`
characters (saying how much was cut), at most `MAX_EXCHANGES` requests and `MAX_NOTES` notes are kept.

>>> recorder = TraceRecorder(dialogue_id="d1", speaker="alice", input="hi")
>>> with recorder.stage("ground"):
...     pass
>>> trace = recorder.finish(response="Hello!", backend="rules", answered_by="rules")
>>> trace.answered_by, [s.name for s in trace.stages], trace.stages[-1].name
('rules', ['ground', 'total'], 'total')
"""

from __future__ import annotations

import json
import time
import uuid
from collections import Counter
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from functools import lru_cache
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from dialogue.intents import Intent

#: Longest text kept for one message, answer or note.
MAX_TEXT = 8000
MAX_EXCHANGES = 4
MAX_NOTES = 24

AnsweredBy = Literal["rules", "model", "fallback", "handover", "recorded", "form"]


def clip(text: str, limit: int = MAX_TEXT) -> str:
    """`text`, cut at `limit` characters with a note of how many were left out."""
    if len(text) <= limit:
        return text
    return f"{text[:limit]}… [{len(text) - limit} more characters]"


class Stage(BaseModel):
    """One timed step of the turn (`ground`, `speaker`, `rules`, `model`, `validate`, `total`...)."""

    name: str
    ms: float


class Message(BaseModel):
    """One message of a request (frozen: the traces of a dialogue's turns share their history's)."""

    model_config = ConfigDict(frozen=True)

    role: str
    content: str


class Exchange(BaseModel):
    """One request to a model and its answer."""

    model_config = ConfigDict(populate_by_name=True)

    model: str
    repair: bool = False
    messages: list[Message]
    json_schema: dict[str, Any] = Field(alias="schema", serialization_alias="schema")
    raw_answer: str | None = None
    done_reason: str | None = None
    #: Why the answer could not be used (validation), or why there was none (model error).
    error: str | None = None
    ms: float | None = None

    def chars(self) -> int:
        """About how many characters this exchange holds (the schema counted as its JSON)."""
        texts = (self.raw_answer or "", self.error or "", *(m.content for m in self.messages))
        return sum(map(len, texts)) + len(json.dumps(self.json_schema))


class SnapshotSummary(BaseModel):
    """What the turn knew of the situation: the KB revision, how many entities it knew, the kinds of
    those the prompt showed (the most relevant, ranked per turn) and the first of their ids."""

    revision: int
    entities: int
    #: Kinds of the prompt's entities; counting the whole KB's would cost a turn O(KB size). Empty
    #: when the turn built no prompt (the rules answered it).
    by_kind: dict[str, int]
    #: The most relevant entities of the turn (what the prompt and the schema show first).
    focus: list[str]


class TurnTrace(BaseModel):
    """Everything recorded about one turn; `GET /dialogues/{id}/turns` answers a list of these."""

    id: str
    dialogue_id: str = ""
    at: float
    role: str = "__default__"
    #: "3.0" (the service keeps the history) or "4.0" (the request brings it: stateless).
    shape: Literal["3.0", "4.0"] = "3.0"
    speaker: str = ""
    input: str = ""
    locale: str | None = None
    snapshot: SnapshotSummary | None = None
    #: The backend's name ("rules", "hybrid:ollama:...", "fallback").
    backend: str = ""
    answered_by: AnsweredBy | None = None
    exchanges: list[Exchange] = Field(default_factory=list)
    validation_errors: list[str] = Field(default_factory=list)
    #: True when a repair request followed an invalid answer and its answer was used.
    repaired: bool = False
    response: str = ""
    intents: list[Intent] = Field(default_factory=list)
    error_msg: str = ""
    clarify: bool = False
    dialogue_terminal: bool | None = None
    results: str | None = None
    #: What a role did with the turn (the ask role: each field read, corrected, refused, asked).
    notes: list[str] = Field(default_factory=list)
    stages: list[Stage] = Field(default_factory=list)

    def chars(self) -> int:
        """About how many characters the trace holds: what a store's budget counts."""
        texts = (self.input, self.response, self.error_msg, self.results or "", *self.notes)
        return (
            sum(map(len, texts))
            + sum(map(len, self.validation_errors))
            + sum(exchange.chars() for exchange in self.exchanges)
        )


@lru_cache(maxsize=4096)
def _message(role: str, content: str) -> Message:
    """A request's message as the trace records it. A model turn's prompt holds the dialogue's
    history (some 50 messages), the same turn after turn: each trace refers to one shared message
    rather than holding a copy made anew each turn (a tenth of a model turn's own work)."""
    return Message.model_construct(role=role, content=clip(content))


def _ms(start: float) -> float:
    return round((time.perf_counter() - start) * 1000, 3)


class TraceRecorder:
    """Collects a turn's trace while it runs; `finish` makes the `TurnTrace`. One per turn."""

    def __init__(
        self,
        *,
        dialogue_id: str = "",
        role: str = "__default__",
        shape: Literal["3.0", "4.0"] = "3.0",
        speaker: str = "",
        input: str = "",
        locale: str | None = None,
    ) -> None:
        self._start = time.perf_counter()
        self.trace = TurnTrace(
            id=uuid.uuid4().hex,
            dialogue_id=dialogue_id,
            at=time.time(),
            role=role,
            shape=shape,
            speaker=speaker,
            input=clip(input),
            locale=locale,
        )

    @contextmanager
    def stage(self, name: str) -> Iterator[None]:
        start = time.perf_counter()
        try:
            yield
        finally:
            self.trace.stages.append(Stage(name=name, ms=_ms(start)))

    def snapshot(self, revision: int, entities: int, kinds: Sequence[str] = (),
                 focus: Sequence[str] = ()) -> None:
        """`entities`: how many the snapshot holds; `kinds` and `focus`: of the prompt's entities
        (none when the turn built no prompt: `shown` adds them when it does)."""
        self.trace.snapshot = SnapshotSummary(
            revision=revision, entities=entities, by_kind=dict(Counter(kinds)), focus=list(focus[:12])
        )

    def shown(self, kinds: Sequence[str], focus: Sequence[str]) -> None:
        """The kinds and ids of the entities the turn's prompt and schema show."""
        if self.trace.snapshot is not None:
            self.trace.snapshot.by_kind = dict(Counter(kinds))
            self.trace.snapshot.focus = list(focus[:12])

    def request(
        self, model: str, messages: Sequence[tuple[str, str]], schema: dict[str, Any], repair: bool = False
    ) -> Exchange | None:
        """Record a request about to be sent; fill in its answer on the returned exchange."""
        if len(self.trace.exchanges) >= MAX_EXCHANGES:
            return None
        # Built without validating the schema again (it cost more than the rest of a model turn).
        exchange = Exchange.model_construct(
            model=model, repair=repair, json_schema=schema, messages=[_message(r, c) for r, c in messages]
        )
        self.trace.exchanges.append(exchange)
        return exchange

    @staticmethod
    def answered(
        exchange: Exchange | None,
        raw: str | None,
        done_reason: str | None,
        started: float,
        error: str | None = None,
    ) -> None:
        if exchange is not None:
            exchange.raw_answer = None if raw is None else clip(raw)
            exchange.done_reason = done_reason
            exchange.error = None if error is None else clip(error)
            exchange.ms = _ms(started)

    def invalid(self, exchange: Exchange | None, error: str) -> None:
        self.trace.validation_errors.append(clip(error))
        if exchange is not None:
            exchange.error = clip(error)

    def note(self, text: str) -> None:
        if len(self.trace.notes) < MAX_NOTES:
            self.trace.notes.append(clip(text, 500))

    def finish(
        self,
        *,
        response: str,
        backend: str,
        answered_by: AnsweredBy | None,
        intents: Sequence[Intent] = (),
        error_msg: str = "",
        clarify: bool = False,
        dialogue_terminal: bool | None = None,
        results: str | None = None,
    ) -> TurnTrace:
        trace = self.trace
        if not trace.stages or trace.stages[-1].name != "total":
            trace.stages.append(Stage(name="total", ms=_ms(self._start)))
        # The turn's outcome is set on the one copy made (each attribute set on a pydantic model is
        # three calls), and what the recorder could still change is copied, one level deep (a deep
        # copy of the pydantic models was a tenth of a rules turn): its lists, and each exchange.
        return trace.model_copy(update={
            "response": clip(response), "backend": backend, "answered_by": answered_by,
            "intents": list(intents), "error_msg": clip(error_msg), "clarify": clarify,
            "dialogue_terminal": dialogue_terminal, "results": results,
            "repaired": bool(trace.validation_errors) and answered_by == "model" and not error_msg,
            "stages": list(trace.stages), "validation_errors": list(trace.validation_errors),
            "notes": list(trace.notes), "exchanges": [exchange.model_copy() for exchange in trace.exchanges],
            "snapshot": trace.snapshot.model_copy() if trace.snapshot is not None else None,
        })  # fmt: skip
