"""An intent pushed from outside (POST /intents) meets the Intent contract and names KB entities."""

from __future__ import annotations

import pytest

from dialogue import intents as I
from dialogue.pushed.events import Emitted
from dialogue.pushed.incoming import IncomingError, IncomingTooLarge, check_incoming
from kb import KB


@pytest.fixture
def kb() -> KB:
    kb = KB()
    kb.update(["cup_1 rdf:type dbr:Cup", "person_ana rdf:type Human", "book_1 belongsTo person_tom"])
    return kb


def emitted(intent: str, data: dict[str, str], response: str = "") -> Emitted:
    return Emitted("dialogue", I.Intent(intent=intent, data=data, source="person_ana"), "d", response, 1.0)


def test_a_catalogue_intent_naming_kb_entities_passes(kb: KB) -> None:
    check_incoming(kb, emitted(I.BRING_OBJECT, {"object": "cup_1", "recipient": "person_ana"}), 4096)
    check_incoming(kb, emitted(I.GREET, {"recipient": "person_tom"}), 4096)  # known as an object only
    check_incoming(kb, emitted(I.SAY, {"object": "words, no entity"}), 4096)


@pytest.mark.parametrize(("intent", "data", "message"), [
    ("__intent_fly__", {}, "unknown intent '__intent_fly__'"),
    (I.BRING_OBJECT, {"object": "cup_1"}, "missing required role(s) ['recipient']"),
    (I.GREET, {"recipient": "person_ana", "mood": "happy"}, "GREET has no role 'mood'"),
    (I.GREET, {"recipient": "person_zed"}, "recipient 'person_zed' names nothing in the KB"),
    (I.GRAB_OBJECT, {"object": "?x"}, "object '?x' is not a KB id"),
])
def test_what_breaks_the_contract_is_refused_saying_what(kb: KB, intent: str, data: dict[str, str],
                                                         message: str) -> None:
    with pytest.raises(IncomingError) as refused:
        check_incoming(kb, emitted(intent, data), 4096)
    assert message in str(refused.value)


def test_an_intent_past_the_bytes_is_refused_whatever_carries_them(kb: KB) -> None:
    small = emitted(I.GREET, {"recipient": "person_ana"})
    check_incoming(kb, small, small.size)
    for large in (emitted(I.SAY, {"object": "x" * 5000}), emitted(I.GREET, {"recipient": "person_ana"}, "é" * 2100)):
        with pytest.raises(IncomingTooLarge, match="the limit is 4096 bytes"):
            check_incoming(kb, large, 4096)
