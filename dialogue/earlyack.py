"""The reply spoken before the turn is over: a streamed answer's `verbal_ack`, as soon as the model
has closed that JSON string (the turn schema puts it first, before the intent).

A caller that wants it (the interaction route, for a client asking for `text/event-stream`) runs the
turn inside `acks_to(sink)`; the engine asks its model through `ask()`, which streams when a sink
listens and the backend can stream (dialogue.llm.stream), and feeds the text to an `AckDetector`.
The sink reaches the model through the layers in between (dialogue manager, engine) in a
ContextVar: it belongs to the task running the turn, so concurrent turns never see each other's
sink, and those layers need not carry it.

The ack is provisional. The answer may still fail validation (then a repair or the fallback reply
answers), resolve to a clarifying question, or miss the deadline: the turn's result is what
counts. The sink gets at most one ack per turn, never after the turn has ended.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

from pydantic_core import from_json

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult
from dialogue.llm.stream import StreamingChatModel
from dialogue.validate import MAX_REPLY_CHARS

AckSink = Callable[[str], None]


class _Once:
    """Passes on the first ack of a turn while the turn runs; drops the rest."""

    def __init__(self, sink: AckSink) -> None:
        self._sink = sink
        self.open = True

    def __call__(self, ack: str) -> None:
        if self.open:
            self.open = False
            self._sink(ack)


_LISTENER: ContextVar[_Once | None] = ContextVar("situated_early_ack", default=None)


@contextmanager
def acks_to(sink: AckSink) -> Iterator[None]:
    """Within this block (and tasks started from it), a streamed `verbal_ack` goes to `sink`."""
    once = _Once(sink)
    token = _LISTENER.set(once)
    try:
        yield
    finally:
        once.open = False  # a generation still running after the turn ended sends nothing
        _LISTENER.reset(token)


def read_ack(text: str) -> tuple[str | None, bool]:
    """The leading `verbal_ack` of partial JSON `text` so far, and whether its string is closed.

    (None, True): the answer does not start with a `verbal_ack` string (null, another key first,
    not JSON) — there will be no early ack. (None, False): not enough text yet.
    """
    start = text.find("{")
    if start < 0:
        return None, False
    try:
        closed = from_json(text[start:], allow_partial=True)
        partial = from_json(text[start:], allow_partial="trailing-strings")
    except ValueError:
        return None, True
    if not isinstance(closed, dict) or not isinstance(partial, dict):
        return None, True
    if "verbal_ack" in closed:
        value = closed["verbal_ack"]
        return (value, True) if isinstance(value, str) else (None, True)
    if partial and next(iter(partial)) != "verbal_ack":
        return None, True
    value = partial.get("verbal_ack")
    return (value, False) if isinstance(value, str) else (None, False)


def spoken(ack: str) -> str:
    """The ack as the turn's reply would say it (dialogue.validate trims the same way)."""
    return ack.strip()[:MAX_REPLY_CHARS]


class AckDetector:
    """Fed the streamed content piece by piece; calls `on_ack` once with the answer's `verbal_ack`
    when its string closes — never for null, an empty string, or an answer that starts otherwise."""

    def __init__(self, on_ack: AckSink) -> None:
        self._on_ack = on_ack
        self._text: list[str] = []
        self.done = False

    def feed(self, piece: str) -> None:
        if self.done:
            return
        self._text.append(piece)
        value, closed = read_ack("".join(self._text))
        if not closed:
            return
        self.done = True
        if value is not None and spoken(value):
            self._on_ack(spoken(value))


async def ask(model: ChatModel, request: ChatRequest, timeout: float) -> ChatResult:
    """`model.chat(request, timeout)`, streamed into the turn's ack sink when there is one."""
    listener = _LISTENER.get()
    if listener is None or not listener.open or not isinstance(model, StreamingChatModel):
        return await model.chat(request, timeout)
    return await model.chat_stream(request, timeout, AckDetector(listener).feed)
