"""The writer's side of a KB kept in a SPARQL 1.1 store: every commit becomes one update request.

The writer process keeps its in-process KB (the incremental reasoner needs the closure at hand)
and mirrors it to the store, where any number of reader processes (kb.remote.RemoteKB) answer
queries. For each commit the mirror sends ONE update request holding the asserted and inferred
changes of every model it touched and the new revision (kb.layout), so readers see whole
commits only. It runs as a commit listener, under the KB lock, before the commit is acknowledged:
when the store refuses or cannot be reached, the writer undoes the batch and the caller gets
``StoreUnavailable``. After any failure the mirror no longer trusts what the store holds and the
next commit rewrites the whole dataset.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING

from rdflib import Literal, Variable

from kb import sparqltext as text
from kb.endpoint import SparqlEndpoint, StoreUnavailable
from kb.layout import MODEL, REVISION
from kb.remotequery import StoreQueries
from kb.store import Delta, Model
from kb.terms import Triple
from kb.writer import Commit, Writer

if TYPE_CHECKING:
    from kb.kb import KB

log = logging.getLogger(__name__)


class SparqlMirror:
    """Keeps one dataset of a SPARQL store equal to a KB (asserted and inferred graphs)."""

    def __init__(self, endpoint: SparqlEndpoint) -> None:
        self.endpoint = endpoint
        self.layout = endpoint.layout
        self._queries = StoreQueries(endpoint)
        self._writer: Writer | None = None
        self._unregister: Callable[[], None] | None = None
        self._stale = True
        self._known_models: set[str] = set()

    @property
    def stale(self) -> bool:
        """True when the store may differ from the KB (until the next successful commit)."""
        return self._stale

    def stored_models(self) -> list[str]:
        """The models the dataset holds now (from its meta graph)."""
        return sorted(self._queries.meta().models)

    def stored_revision(self) -> int | None:
        return self._queries.meta().revision

    def recover(self, kb: KB) -> int | None:
        """Load the asserted triples the store holds into an empty writer (the store as the
        durable copy when no journal is kept); returns the stored revision, None if the dataset
        is empty. Inferred triples are derived again; lifespans are not stored."""
        meta = self._queries.meta()
        if meta.revision is None:
            return None
        writer = kb.writer
        for model in meta.models:
            stored = set(self._queries.triples(self._queries.graphs(model), inferred=False))
            with writer.lock:
                current = writer.models.get(model)
                have = set(current.asserted) if current is not None else set()
                writer.restore(model, sorted(stored - have, key=str), sorted(have - stored, key=str), [],
                               revision=meta.revision)
        return meta.revision

    def attach(self, kb: KB) -> None:
        """Rewrite the dataset from the KB, then mirror every commit."""
        writer = kb.writer
        with writer.lock:
            self._writer = writer
            self.push_all()
            self._unregister = writer.on_commit(self._on_commit, durable=True)

    def detach(self) -> None:
        if self._unregister is not None:
            self._unregister()
        self._unregister, self._writer = None, None

    def push_all(self) -> None:
        """Replace the whole dataset by the KB's state, in one update (call under the KB lock)."""
        writer = self._require_writer()
        stored = set(self.stored_models()) if not self._known_models else set(self._known_models)
        models = [m for n in writer.models.names if (m := writer.models.get(n)) is not None]
        operations = [f"DROP SILENT GRAPH {text.term(g)}"
                      for name in sorted(stored | {m.name for m in models}) for g in self.layout.graphs(name)]
        operations.append(f"DROP SILENT GRAPH {text.term(self.layout.meta)}")
        operations.extend(self._whole(model) for model in models)
        operations.append(_insert([text.graph_data(self.layout.meta, self._meta(writer.revision, models))]))
        self._send(operations)
        self._known_models = {m.name for m in models}

    def _on_commit(self, commit: Commit) -> None:
        writer = self._require_writer()
        if self._stale or commit.cleared is not None:
            self.push_all()
            return
        operations: list[str] = []
        new_models: list[Model] = []
        for delta in commit.deltas:
            model = writer.models.get(delta.model)
            if model is None:
                continue
            if model.name in self._known_models:
                operations.extend(self._delta(model, delta))
            else:  # a new model starts from the default ontology, not only from this batch
                new_models.append(model)
                operations.append(self._whole(model))
        meta = self.layout.meta
        operations.append(f"DELETE WHERE {{ GRAPH {text.term(meta)} {{ "
                          f"{text.triple(self.layout.root, REVISION, Variable('r'))} }} }}")
        operations.append(_insert([text.graph_data(meta, self._meta(commit.revision, new_models))]))
        self._send(operations)
        self._known_models.update(m.name for m in new_models)

    def _whole(self, model: Model) -> str:
        inferred = (t for t in model.closure if t not in model.asserted)
        return _insert([text.graph_data(self.layout.asserted(model.name), model.asserted),
                        text.graph_data(self.layout.inferred(model.name), inferred)])

    def _delta(self, model: Model, delta: Delta) -> list[str]:
        """The asserted changes as they are; the inferred graph (closure minus asserted) gains
        and loses exactly the triples whose status changed."""
        asserted_added, asserted_removed = set(delta.asserted_added), set(delta.asserted_removed)
        added, removed = set(delta.added), set(delta.removed)
        inferred_in: list[Triple] = []
        inferred_out: list[Triple] = []
        for t in asserted_added | asserted_removed | added | removed:
            now = t in model.closure and t not in model.asserted
            closure_before = (t in model.closure and t not in added) or t in removed
            asserted_before = (t in model.asserted and t not in asserted_added) or t in asserted_removed
            before = closure_before and not asserted_before
            if now and not before:
                inferred_in.append(t)
            elif before and not now:
                inferred_out.append(t)
        asserted_g, inferred_g = self.layout.graphs(model.name)
        operations = []
        removals = [text.graph_data(asserted_g, asserted_removed), text.graph_data(inferred_g, inferred_out)]
        if any(removals):
            operations.append("DELETE DATA {\n" + "\n".join(r for r in removals if r) + "\n}")
        additions = [text.graph_data(asserted_g, asserted_added), text.graph_data(inferred_g, inferred_in)]
        if any(additions):
            operations.append(_insert(additions))
        return operations

    def _meta(self, revision: int, models: Iterable[Model]) -> list[Triple]:
        root = self.layout.root
        triples: list[Triple] = [(root, REVISION, Literal(revision))]
        triples.extend((root, MODEL, Literal(m.name)) for m in models)
        return triples

    def _send(self, operations: list[str]) -> None:
        try:
            self.endpoint.update(" ;\n".join(operations))
        except StoreUnavailable:
            self._stale = True  # the request may or may not have been applied
            raise
        self._stale = False

    def _require_writer(self) -> Writer:
        if self._writer is None:
            raise RuntimeError("the mirror is not attached to a KB")
        return self._writer


def _insert(graphs: list[str]) -> str:
    return "INSERT DATA {\n" + "\n".join(g for g in graphs if g) + "\n}"

