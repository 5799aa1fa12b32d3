"""Dialogue sessions in a SPARQL 1.1 store, shared by every service process that uses the store.

In the graph ``layout.dialogues`` each dialogue ``layout.dialogue(id)`` has two triples: its state
as one JSON literal (``sit:dialogueState``, see dialogue.sessions.store.DialogueState) and when it
was last saved (``sit:touched``, an ``xsd:dateTime``) that orders the eviction. A load is one
SELECT; a save, a delete, an id listing are one request each. Every request is written with
kb.sparqlstore.text from rdflib terms, so no id or text can break out of its term.

Each update request is applied whole or not at all by the store; concurrent saves of one dialogue
from different processes are not merged: the last one wins (see dialogue.sessions.manager).
"""

from __future__ import annotations

from datetime import UTC, datetime
from typing import ClassVar, Final
from urllib.parse import unquote

from rdflib import Literal, URIRef, Variable

from dialogue.sessions.store import DEFAULT_DIALOGUE, DialogueState, StateError, check_bound
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.layout import SIT
from kb.sparqlstore.text import term

STATE: Final = URIRef(SIT + "dialogueState")
TOUCHED: Final = URIRef(SIT + "touched")

_S, _T, _D, _P, _O = (Variable(n) for n in ("state", "touched", "d", "p", "o"))


def _stamp(seconds: float) -> Literal:
    return Literal(datetime.fromtimestamp(seconds, tz=UTC))


class SparqlSessions:
    """`SessionStore` in the dataset `endpoint` names; calls block on the store (StoreUnavailable)."""

    blocking: ClassVar[bool] = True

    def __init__(self, endpoint: SparqlEndpoint, max_dialogues: int = 256) -> None:
        self.max_dialogues = check_bound(max_dialogues)
        self.endpoint = endpoint
        self.layout = endpoint.layout
        self._graph = term(self.layout.dialogues)
        self._prefix = str(self.layout.dialogue(""))

    def _iri(self, dialogue_id: str) -> str:
        return term(self.layout.dialogue(dialogue_id))

    def load(self, dialogue_id: str) -> DialogueState | None:
        d = self._iri(dialogue_id)
        rows = self.endpoint.select(
            f"SELECT {term(_S)} WHERE {{ GRAPH {self._graph} {{ {d} {term(STATE)} {term(_S)} }} }}"
        )
        states = [self._state(row.get(str(_S)), dialogue_id) for row in rows]
        # Two processes saving one dialogue at once may both replace the state they read (the store
        # isolates the updates as snapshots, it does not serialise them): the last saved one wins.
        return max(states, key=lambda s: s.last_used, default=None)

    @staticmethod
    def _state(value: object, dialogue_id: str) -> DialogueState:
        if not isinstance(value, Literal):
            raise StateError(f"the stored state is {value!r}, not a JSON literal")
        state = DialogueState.from_json(str(value))
        if state.id != dialogue_id:
            raise StateError(f"the stored state is that of dialogue {state.id!r}")
        return state

    def save(self, state: DialogueState, *, create: bool = False) -> None:
        d, g = self._iri(state.id), self._graph
        old_state = f"GRAPH {g} {{ {d} {term(STATE)} {term(_S)} }}"
        old_touched = f"GRAPH {g} {{ {d} {term(TOUCHED)} {term(_T)} }}"
        # Without `create` the WHERE needs the stored state, so an ended dialogue is not stored again;
        # with it, both are optional (one empty solution when absent: the insert still happens).
        where = (
            f"OPTIONAL {{ {old_state} }} OPTIONAL {{ {old_touched} }}"
            if create
            else f"{old_state} OPTIONAL {{ {old_touched} }}"
        )
        update = (
            f"DELETE {{ GRAPH {g} {{ {d} {term(STATE)} {term(_S)} . {d} {term(TOUCHED)} {term(_T)} . }} }}\n"
            f"INSERT {{ GRAPH {g} {{ {d} {term(STATE)} {term(Literal(state.to_json()))} . "
            f"{d} {term(TOUCHED)} {term(_stamp(state.last_used))} . }} }}\n"
            f"WHERE {{ {where} }}"
        )
        if create:
            update += ";\n" + self._evict()
        self.endpoint.update(update)

    def _evict(self) -> str:
        """Drops all but the `max_dialogues - 1` most recently saved dialogues besides `default`."""
        g, d = self._graph, term(_D)
        keep = self.max_dialogues - 1
        return (
            f"DELETE {{ GRAPH {g} {{ {d} {term(_P)} {term(_O)} }} }}\n"
            f"WHERE {{ {{ SELECT {d} WHERE {{ GRAPH {g} {{ {d} {term(TOUCHED)} {term(_T)} }} "
            f"FILTER({d} != {self._iri(DEFAULT_DIALOGUE)}) }} GROUP BY {d} ORDER BY DESC(MAX({term(_T)})) "
            f"OFFSET {keep:d} }}\n"
            f"GRAPH {g} {{ {d} {term(_P)} {term(_O)} }} }}"
        )

    def delete(self, dialogue_id: str) -> None:
        d = self._iri(dialogue_id)
        self.endpoint.update(f"DELETE WHERE {{ GRAPH {self._graph} {{ {d} {term(_P)} {term(_O)} }} }}")

    def ids(self) -> list[str]:
        d = term(_D)
        rows = self.endpoint.select(
            f"SELECT {d} WHERE {{ GRAPH {self._graph} {{ {d} {term(TOUCHED)} {term(_T)} }} }} "
            f"GROUP BY {d} ORDER BY MAX({term(_T)})"
        )
        out = []
        for row in rows:
            iri = str(row[str(_D)])
            if not iri.startswith(self._prefix):
                raise StateError(f"{iri!r} in {self.layout.dialogues} is not a dialogue of this dataset")
            out.append(unquote(iri[len(self._prefix):]))
        return out
