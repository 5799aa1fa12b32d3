"""Subscriptions of a read replica (kb.sparqlstore.events): polling sees other processes' commits, a
write through the replica returns once it was evaluated, one-shot, unsubscribe, the thread's life,
and active concepts. The fixture-based tables of test_events.py run against RemoteKB too."""

from __future__ import annotations

import threading
from collections.abc import Callable
from contextlib import AbstractContextManager

import pytest

from kb import KbError
from kb.errors import TooManyRows
from kb.sparqlstore.remote import RemoteKB
from tests.conftest import Replica
from tests.kb.test_events import Recorder
from tests.waiting import until

Replicas = Callable[..., AbstractContextManager[Replica]]


def test_polling_sees_commits_made_by_the_writer(replicas: Replicas) -> None:
    with replicas() as replica:
        reader, writer = replica.reader, replica.writer
        assert not _poll_threads(reader)
        rec, once = Recorder(), Recorder()
        reader.subscribe("?x sees cup", rec)
        sid = reader.subscribe("?x sees ?y", once, one_shot=True)
        assert len(_poll_threads(reader)) == 1
        writer.add("alfred sees cup")  # another process's write: the reader polls for it
        until(lambda: rec.calls == [[{"x": "alfred"}]])
        until(lambda: once.calls == [[{"x": "alfred", "y": "cup"}]])
        assert reader.unsubscribe(sid) is False  # the one-shot went after firing
        assert rec.take() == [[{"x": "alfred"}]]
        writer.remove("alfred sees cup")
        reader.settle()  # without it, the removal and the return could fall between two polls
        writer.add("alfred sees cup")
        reader.settle()
        assert rec.take() == [[{"x": "alfred"}]]
        reader.update("bob sees cup")  # a write through the reader returns once it was evaluated
        assert rec.take() == [[{"x": "bob"}]]
        reader.close()
        assert not _poll_threads(reader)
        with pytest.raises(KbError, match="closed"):
            reader.subscribe("?x sees cup", rec)


def _poll_threads(reader: RemoteKB) -> list[threading.Thread]:
    return [t for t in threading.enumerate() if t.name == "kb-remote-poll" and t.is_alive()
            and getattr(reader._events, "_thread", None) is t]


def test_active_concepts_are_polled(replicas: Replicas) -> None:
    with replicas() as replica:
        seen: list[list[str]] = []
        replica.reader.on_active_concept(seen.append)
        replica.reader.add(["cup_1 rdf:type ActiveConcept", "cup_1 rdf:type dbr:Cup"])
        assert seen == [["cup_1"]]
        replica.reader.remove("cup_1 rdf:type ActiveConcept")
        assert seen == [["cup_1"], []]


def test_an_active_concept_listener_can_be_removed(replicas: Replicas) -> None:
    with replicas() as replica:
        seen: list[list[str]] = []
        stop = replica.reader.on_active_concept(seen.append)
        replica.reader.add("cup_1 rdf:type ActiveConcept")
        stop()
        replica.reader.add("book_1 rdf:type ActiveConcept")
        assert seen == [["cup_1"]]


def test_a_replica_subscription_is_bounded_like_the_writers(replicas: Replicas) -> None:
    with replicas() as replica:
        reader, writer = replica.reader, replica.writer
        writer.add([f"thing_{i} isOn table_1" for i in range(5)])
        with pytest.raises(TooManyRows, match="more than 3 rows"):
            reader.subscribe("?x isOn ?t", Recorder(), max_rows=3)
        rec, errors = Recorder(), Recorder()
        reader.subscribe(["?x isOn ?t", "?t rdf:type Table"], rec, max_rows=6, timeout=30.0,
                         on_error=errors)
        writer.add("table_1 rdf:type Table")
        reader.settle()
        assert len(rec.take()) == 1 and errors.calls == []
        writer.add(["thing_5 isOn table_1", "thing_6 isOn table_1"])  # seven rows: past the cap
        reader.settle()
        assert rec.calls == [] and len(errors.calls) == 1 and isinstance(errors.calls[0], TooManyRows)
        writer.add("thing_7 isOn table_1")
        reader.settle()
        assert rec.calls == [] and len(errors.calls) == 1  # ended: no longer evaluated
