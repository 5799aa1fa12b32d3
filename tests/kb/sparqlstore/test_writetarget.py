"""ReplicaWrites (kb.sparqlstore.writetarget): a read replica checks writes exactly as KB does (same errors,
before anything is sent), forwards them as given to its write target, and without one refuses
them as a read-only replica."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager
from pathlib import Path
from typing import Any

import pytest

from kb import KB, KbError
from kb.sparqlstore.remote import RemoteKB
from tests.conftest import Replica

Replicas = Callable[..., AbstractContextManager[Replica]]


@pytest.fixture(scope="module")
def local() -> Iterator[KB]:
    with KB() as kb:
        yield kb


class RecordingTarget:
    """A write target that records what reaches it (nothing must, when a write is refused)."""

    def __init__(self) -> None:
        self.calls: list[tuple[str, tuple[Any, ...]]] = []

    def __getattr__(self, name: str) -> Any:
        if name not in ("update", "remove", "apply", "apply_models", "clear", "load_data", "sparql_update"):
            raise AttributeError(name)
        return lambda *args: self.calls.append((name, args))


BAD_WRITES: dict[str, Callable[[Any], Any]] = {
    "three terms": lambda k: k.add(["x sees"]),
    "variable": lambda k: k.update("x sees ?y"),
    "prefix": lambda k: k.remove("?x zz:p ?y"),
    "model": lambda k: k.add("x sees y", models=["bad name"]),
    "lifespan": lambda k: k.update("x sees y", lifespan=-1),
    "apply": lambda k: k.apply(add=["x sees y"], remove=["x sees"]),
    "apply models": lambda k: k.apply_models({"bob": {"add": ["x sees y"]}, "default": {"remove": ["x sees"]}}),
    "apply models shape": lambda k: k.apply_models({"bob": ["x sees y"]}),
    "policy": lambda k: k.revise("x sees y", {"method": "frobnicate"}),
    "load": lambda k: k.load("/no/such/file.ttl"),
    "load type": lambda k: k.load(None),
    "data": lambda k: k.load_data("@prefix : <x> . :a :b", "turtle"),
    "format": lambda k: k.load_data("", "nonsensefmt"),
    "sparql update": lambda k: k.sparql_update("DELETE WHERE { ?s ?p ?o }"),
    "statements": lambda k: k.add(["x sees y", None]),
}


@pytest.mark.parametrize("call", list(BAD_WRITES.values()), ids=list(BAD_WRITES))
def test_bad_writes_get_the_errors_of_kb_and_reach_nobody(
        local: KB, store: Callable[[], str], call: Callable[[Any], Any]) -> None:
    target = RecordingTarget()
    revision = local.revision
    with RemoteKB(store(), writes=target) as remote:  # type: ignore[arg-type]
        with pytest.raises(KbError) as expected:
            call(local)
        with pytest.raises(KbError) as got:
            call(remote)
    assert type(got.value) is type(expected.value)
    assert str(got.value) == str(expected.value)
    assert target.calls == []
    assert local.revision == revision


def test_good_writes_are_forwarded_as_given(store: Callable[[], str], tmp_path: Path) -> None:
    target = RecordingTarget()
    document = tmp_path / "extra.ttl"
    document.write_text("@prefix : <http://kb.openrobots.org#> .\n:a :sees :b .\n")
    with RemoteKB(store(), writes=target) as remote:  # type: ignore[arg-type]
        remote += "x sees y"
        remote.revise(["x sees ?y"], {"method": "retract", "models": ["bob"]})
        remote.apply(add=["x sees z"], remove=["x sees y"], lifespan=5)
        remote.apply_models({"bob": {"add": "x sees b"}, "default": {"remove": ["x sees z"]}})
        remote.load(document, models=["bob"])
        remote.sparql_update("INSERT DATA { oro:x oro:sees oro:w }")
        remote.clear(keep_defaults=False)
    assert target.calls == [
        ("update", (["x sees y"], None, 0)),
        ("remove", (["x sees ?y"], ["bob"])),
        ("apply", (["x sees z"], ["x sees y"], None, 5)),
        ("apply_models", ({"bob": {"add": ["x sees b"], "remove": []}, "default": {"add": [], "remove": ["x sees z"]}},
                          0.0)),
        ("load_data", (document.read_bytes(), "turtle", ["bob"])),
        ("sparql_update", ("INSERT DATA { oro:x oro:sees oro:w }", None)),
        ("clear", (False,)),
    ]


def test_without_a_writer_the_replica_is_read_only(replicas: Replicas, tmp_path: Path) -> None:
    with replicas() as replica, RemoteKB(replica.store) as reader:
        replica.writer.add("myself sees cup_1")
        revision = replica.writer.revision
        writes: list[Callable[[], Any]] = [
            lambda: reader.add("myself sees cup_2"), lambda: reader.remove("myself sees ?x"),
            lambda: reader.apply(add=["a sees b"]), lambda: reader.clear(),
            lambda: reader.apply_models({"bob": {"add": ["a sees b"]}}),
            lambda: reader.load_data("<http://a> <http://b> <http://c> .", "nt"),
            lambda: reader.sparql_update("INSERT DATA { oro:a oro:b oro:c }"),
            lambda: reader.revise("a sees b", {"method": "add"}), lambda: reader.load(tmp_path / "x.ttl"),
        ]
        for write in writes:
            with pytest.raises(KbError, match="read-only replica"):
                write()
        with pytest.raises(KbError, match="read-only replica"):
            reader += "myself sees cup_3"
        assert replica.writer.revision == revision
        assert reader["myself sees ?x"] == [{"x": "cup_1"}]


def test_a_write_target_must_have_the_write_methods(store: Callable[[], str]) -> None:
    with pytest.raises(KbError, match="write target"):
        RemoteKB(store(), writes=object())  # type: ignore[arg-type]
    with pytest.raises(KbError, match="poll_interval"):
        RemoteKB(store(), poll_interval=0)
