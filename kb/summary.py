"""``Summary``: the KB's counts after its last change, readable without the KB lock.

``/health`` must answer while a long query holds the KB (issue 19, item 8). The writer builds a
new summary under the lock at the end of every change and swaps it in with one assignment, so
a reader of ``Writer.summary`` gets one consistent state without waiting for anyone.
"""

from __future__ import annotations

from dataclasses import dataclass

from kb.models import Models


@dataclass(frozen=True)
class Summary:
    revision: int
    size: int  # triples of the default model, inferred ones included
    asserted: int  # asserted triples of the default model
    models: tuple[str, ...]


def summarise(revision: int, models: Models) -> Summary:
    """The summary of the models as they are (call under the KB lock)."""
    default = models.default
    return Summary(revision, len(default.closure), len(default.asserted), tuple(models.names))
