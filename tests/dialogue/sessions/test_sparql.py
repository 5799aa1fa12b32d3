"""Dialogue sessions shared through a SPARQL store: two managers (two "processes", each with its own
engine and connection) on one dataset of a local Oxigraph (the session fixture of tests/conftest.py;
these tests are skipped when the `oxigraph` command is missing)."""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from datetime import UTC, datetime

import pytest
from rdflib import Literal

from dialogue import intents as I
from dialogue.engine import DialogueEngine
from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.llm.base import ChatRequest, ModelError
from dialogue.llm.testing import FunctionModel
from dialogue.sessions.manager import DEFAULT_DIALOGUE, DialogueManager, SessionError
from dialogue.sessions.sparql import STATE, TOUCHED, SparqlSessions
from dialogue.sessions.store import DialogueState
from kb import KB
from kb.errors import StoreUnavailable
from kb.sparqlstore import text as sparqltext
from kb.sparqlstore.endpoint import SparqlEndpoint

HOSTILE_IDS = [
    'quote"d',
    "new\nline",
    "brace}{",
    "angle>bracket<",
    "per%2Fcent/slash ? # &",
    "tab\tand space",
    "back\\slash'",
    "ünïcødé ☕ 日本語 👋",
    "} } . DROP ALL ; INSERT DATA { <a> <b> <c> }",
]
HOSTILE_TEXT = 'she said "hi"\n}} > <x> \\ \' ; DROP ALL # ☕ 👋\r\tend'


@dataclass
class Shared:
    """Two managers sharing one dataset, plus the raw endpoint to look at the store."""

    a: DialogueManager
    b: DialogueManager
    endpoint: SparqlEndpoint


@pytest.fixture
def shared(store: Callable[[], str]) -> Iterator[Callable[..., Shared]]:
    """``shared(kb, max_dialogues=..., model_a=...)``: managers A and B on one fresh dataset."""
    endpoints: list[SparqlEndpoint] = []

    def make(kb: KB, max_dialogues: int = 256, model_a: FunctionModel | None = None) -> Shared:
        url = store()
        a_end, b_end, raw = SparqlEndpoint(url), SparqlEndpoint(url), SparqlEndpoint(url)
        endpoints.extend((a_end, b_end, raw))
        a = DialogueManager(DialogueEngine(kb, model_a), store=SparqlSessions(a_end, max_dialogues))
        b = DialogueManager(DialogueEngine(kb), store=SparqlSessions(b_end, max_dialogues))
        return Shared(a, b, raw)

    yield make
    for endpoint in endpoints[2::3]:
        endpoint.update(f"DROP SILENT GRAPH {sparqltext.term(endpoint.layout.dialogues)}")
    for endpoint in endpoints:
        endpoint.close()


def test_a_dialogue_started_on_one_process_continues_on_the_other(kitchen: KB, shared: Callable[..., Shared]) -> None:
    s = shared(kitchen)
    started = s.a.start(locale="en_GB", configuration='{"persona": "butler"}')
    seen = s.b.get(started.id)
    assert (seen.role, seen.locale, seen.configuration, seen.history) == ("__default__", "en_GB", '{"persona": "butler"}', ())
    assert started.id in s.b.ids()

    asyncio.run(s.a.interact("person_alice", "hello", dialogue_id=started.id))
    result = asyncio.run(s.b.interact("person_alice", "bla bla", dialogue_id=started.id))
    # The locale stored by A reaches B's fallback intent.
    assert result.intents[0].intent == I.RAW_USER_INPUT and result.intents[0].data["locale"] == "en_GB"
    said = [(u.speaker, u.text) for u in s.a.get(started.id).history]
    assert said == [
        ("person_alice", "hello"),
        (ASSISTANT_USER_ID, "Hello Alice!"),
        ("person_alice", "bla bla"),
        (ASSISTANT_USER_ID, result.response),
    ]


def test_a_clarification_asked_by_one_is_answered_through_the_other(cups: KB, shared: Callable[..., Shared]) -> None:
    s = shared(cups)
    d = s.a.start()
    question = asyncio.run(s.a.interact("person_nina", "pick up the cup", dialogue_id=d.id))
    assert question.intents == () and question.clarify and question.response.endswith("?")
    answer = asyncio.run(s.b.interact("person_nina", "the red one", dialogue_id=d.id))
    assert answer.intents[0].intent == I.GRAB_OBJECT and answer.intents[0].data == {"object": "cup_red"}
    # Same through `default`, which neither process started.
    asyncio.run(s.b.interact("person_nina", "pick up the cup"))
    again = asyncio.run(s.a.interact("person_nina", "the blue one"))
    assert again.intents[0].data == {"object": "cup_blue"}


def test_ending_on_one_is_seen_by_the_other(kitchen: KB, shared: Callable[..., Shared]) -> None:
    s = shared(kitchen)
    d = s.a.start()
    asyncio.run(s.a.interact("person_alice", "hello", dialogue_id=d.id))
    s.b.end(d.id)
    with pytest.raises(SessionError, match="unknown dialogue"):
        s.a.get(d.id)
    with pytest.raises(SessionError, match="unknown dialogue"):
        asyncio.run(s.a.interact("person_alice", "hello", dialogue_id=d.id))
    assert d.id not in s.a.ids()
    # `default` always exists; ending it on one process clears the history both see.
    asyncio.run(s.a.interact("person_alice", "hello"))
    assert len(s.b.get(DEFAULT_DIALOGUE).history) == 2
    asyncio.run(s.b.end_async(DEFAULT_DIALOGUE))
    assert s.a.get(DEFAULT_DIALOGUE).history == () and DEFAULT_DIALOGUE in s.a.ids()


def test_a_dialogue_ended_during_a_turn_stays_ended(kitchen: KB, shared: Callable[..., Shared]) -> None:
    box: dict[str, Shared] = {}

    def end_it_elsewhere(request: ChatRequest) -> ModelError:
        box["s"].b.end(dialogue_id)  # another process ends the dialogue while A's model thinks
        return ModelError("no answer")

    s = box["s"] = shared(kitchen, model_a=FunctionModel(end_it_elsewhere))
    dialogue_id = s.a.start().id
    result = asyncio.run(s.a.interact("person_alice", "what is the weather like", dialogue_id=dialogue_id))
    assert result.backend == "fallback"
    with pytest.raises(SessionError, match="unknown dialogue"):
        s.b.get(dialogue_id)


def test_at_most_max_dialogues_are_kept_and_default_is_never_dropped(kitchen: KB, shared: Callable[..., Shared]) -> None:
    s = shared(kitchen, max_dialogues=3)
    asyncio.run(s.a.interact("p", "first", response_expected=False))  # stores `default`, the oldest
    first = s.a.start(dialogue_id="first").id
    s.b.start(dialogue_id="second")
    asyncio.run(s.b.interact("p", "still here", dialogue_id=first, response_expected=False))  # first is used again
    s.a.start(dialogue_id="third")
    assert s.b.ids() == [DEFAULT_DIALOGUE, first, "third"]
    assert s.a.ids() == s.b.ids()
    with pytest.raises(SessionError, match="unknown dialogue 'second'"):
        s.a.get("second")
    assert [u.text for u in s.b.get(DEFAULT_DIALOGUE).history] == ["first"]
    rows = s.endpoint.select(
        f"SELECT ?d WHERE {{ GRAPH {sparqltext.term(s.endpoint.layout.dialogues)} {{ ?d ?p ?o }} }}"
    )
    assert len(rows) == 3 * 2  # nothing of the dropped dialogue is left: one state, one stamp each


@pytest.mark.parametrize("dialogue_id", HOSTILE_IDS)
def test_hostile_ids_and_text_round_trip(dialogue_id: str, kitchen: KB, shared: Callable[..., Shared]) -> None:
    s = shared(kitchen)
    with pytest.raises(SessionError, match="is not a language tag"):  # a locale is checked, never stored as is
        s.a.start(locale=HOSTILE_TEXT, dialogue_id=dialogue_id)
    configuration = json.dumps({"note": HOSTILE_TEXT})  # a role's configuration is a JSON object
    s.a.start(locale="fr-fr", configuration=configuration, dialogue_id=dialogue_id)
    with pytest.raises(SessionError, match="already exists"):
        s.b.start(dialogue_id=dialogue_id)
    asyncio.run(s.b.interact(HOSTILE_TEXT, HOSTILE_TEXT, dialogue_id=dialogue_id, response_expected=False))
    state = s.a.get(dialogue_id)
    assert (state.id, state.locale, state.configuration) == (dialogue_id, "fr_FR", configuration)
    assert state.history == (Utterance(HOSTILE_TEXT, HOSTILE_TEXT),)
    assert s.a.ids() == [DEFAULT_DIALOGUE, dialogue_id]
    s.a.end(dialogue_id)
    assert s.b.ids() == [DEFAULT_DIALOGUE]


def test_text_with_lone_surrogates_and_such_ids_are_refused(kitchen: KB, shared: Callable[..., Shared]) -> None:
    s = shared(kitchen)
    # Not valid Unicode (issue 19, item 7): refused before anything is recorded in the store.
    with pytest.raises(SessionError, match="not valid Unicode"):
        asyncio.run(s.a.interact("p", "broken \ud800 text", response_expected=False))
    assert s.b.get(DEFAULT_DIALOGUE).history == ()
    with pytest.raises(SessionError, match="not valid Unicode text"):
        s.a.start(dialogue_id="bad \udcff id")


def test_concurrent_turns_on_many_dialogues(kitchen: KB, shared: Callable[..., Shared]) -> None:
    s = shared(kitchen)
    ids = [s.a.start().id for _ in range(8)]

    async def turns() -> list[str]:
        results = await asyncio.gather(
            *(m.interact("person_alice", "grab the apple", dialogue_id=i) for i in ids for m in (s.a, s.b))
        )
        return [r.intents[0].data["object"] for r in results]

    assert asyncio.run(turns()) == ["apple_1"] * 16
    # Turns on one dialogue from two processes at once: each saw a consistent state, the last save won.
    assert all(len(s.b.get(i).history) in (2, 4) for i in ids)


def test_an_unreadable_stored_state_is_reported(kitchen: KB, shared: Callable[..., Shared]) -> None:
    s = shared(kitchen)
    d = s.endpoint.layout.dialogue("broken")
    graph = s.endpoint.layout.dialogues
    stamp = Literal(datetime(2024, 1, 1, tzinfo=UTC))
    s.endpoint.update(
        "INSERT DATA { " + sparqltext.graph_data(graph, [(d, STATE, Literal("{not json")), (d, TOUCHED, stamp)]) + " }"
    )
    with pytest.raises(SessionError, match=r"'broken' cannot be read from the store: .*not JSON"):
        s.a.get("broken")
    other = DialogueState("someone_else", last_used=time.time())
    s.endpoint.update(
        "INSERT DATA { " + sparqltext.graph_data(graph, [(s.endpoint.layout.dialogue("moved"), STATE, Literal(other.to_json()))]) + " }"
    )
    with pytest.raises(SessionError, match="that of dialogue 'someone_else'"):
        s.b.get("moved")


def test_an_unreachable_store_is_an_error_not_an_empty_store(kitchen: KB) -> None:
    endpoint = SparqlEndpoint("sparql+http://127.0.0.1:9", timeout=2.0)
    manager = DialogueManager(DialogueEngine(kitchen), store=SparqlSessions(endpoint))
    try:
        with pytest.raises(StoreUnavailable, match="cannot be reached"):
            manager.get(DEFAULT_DIALOGUE)
        # a turn still answers, politely, saying why (issue 19, item 13)
        turn = asyncio.run(manager.interact("p", "hello"))
        assert turn.response and turn.backend == "fallback"
        assert "the dialogue cannot be read" in turn.error_msg and "cannot be reached" in turn.error_msg
    finally:
        endpoint.close()


def test_save_without_create_does_not_store_a_dialogue_again(store: Callable[[], str]) -> None:
    endpoint = SparqlEndpoint(store())
    sessions = SparqlSessions(endpoint)
    try:
        state = DialogueState("gone", history=(Utterance("p", "hi"),), last_used=time.time())
        sessions.save(state)
        assert sessions.load("gone") is None
        sessions.save(state, create=True)
        assert sessions.load("gone") == state
        newer = DialogueState("gone", history=(), last_used=time.time())
        sessions.save(newer)
        assert sessions.load("gone") == newer
        sessions.delete("gone")
        sessions.save(state)
        assert sessions.load("gone") is None and sessions.ids() == []
    finally:
        endpoint.close()


def test_states_left_by_concurrent_saves_resolve_to_the_last_saved(store: Callable[[], str]) -> None:
    # The store isolates concurrent updates as snapshots: two processes replacing the state they
    # both read leave two states (and two stamps). Reads take the last saved; the next save cleans up.
    endpoint = SparqlEndpoint(store())
    sessions = SparqlSessions(endpoint, max_dialogues=2)
    layout = endpoint.layout
    try:
        older = DialogueState("twice", configuration="older", last_used=1000.0)
        newer = DialogueState("twice", configuration="newer", last_used=2000.0)
        d = layout.dialogue("twice")
        triples = [(d, STATE, Literal(s.to_json())) for s in (newer, older)]
        triples += [(d, TOUCHED, Literal(datetime.fromtimestamp(s.last_used, UTC))) for s in (older, newer)]
        endpoint.update("INSERT DATA { " + sparqltext.graph_data(layout.dialogues, triples) + " }")
        assert sessions.load("twice") == newer
        assert sessions.ids() == ["twice"]
        # Bound 2 (`default` + one): "twice", last saved at 2000, is more recent than "other" at 1500.
        sessions.save(DialogueState("other", last_used=1500.0), create=True)
        assert sessions.ids() == ["twice"] and sessions.load("twice") == newer
        endpoint.update("INSERT DATA { " + sparqltext.graph_data(layout.dialogues, triples) + " }")
        sessions.save(DialogueState("twice", configuration="latest", last_used=time.time()))
        rows = endpoint.select(f"SELECT ?p WHERE {{ GRAPH {sparqltext.term(layout.dialogues)} {{ {sparqltext.term(d)} ?p ?o }} }}")
        assert sorted(str(r["p"]) for r in rows) == sorted([str(STATE), str(TOUCHED)])
        latest = sessions.load("twice")
        assert latest is not None and latest.configuration == "latest"
    finally:
        endpoint.update(f"DROP SILENT GRAPH {sparqltext.term(layout.dialogues)}")
        endpoint.close()
