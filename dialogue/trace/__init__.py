"""The trace of every dialogue turn: recorded by the engine as data (`record`), kept bounded per
dialogue (`store`), read with secrets taken out (`redact`)."""

from dialogue.trace.record import TraceRecorder, TurnTrace
from dialogue.trace.redact import redacted
from dialogue.trace.store import TraceStore

__all__ = ["TraceRecorder", "TraceStore", "TurnTrace", "redacted"]
