"""The writer's side of a KB kept in a SPARQL 1.1 store: every commit becomes one update request.

The writer process keeps its in-process KB (the incremental reasoner needs the closure at hand)
and mirrors it to the store, where any number of reader processes (kb.sparqlstore.remote.RemoteKB) answer
queries. For each commit the mirror sends ONE update request holding the asserted and inferred
changes of every model it touched, the new revision and a new write id (kb.sparqlstore.layout), so readers
see whole commits only. It runs as a commit listener, under the KB lock, before the commit is
acknowledged: when the store refuses or cannot be reached, the writer undoes the batch and the
caller gets ``StoreUnavailable``.

An update that was sent but not answered in time (``OutcomeUnknown``) may still be applied by the
store later. Every update applies only where the store still holds the write id it follows
(kb.sparqlstore.mirrortext), so from then on the mirror is *in doubt*: it refuses commits at once, without
contacting the store (the KB lock is never held waiting on a store known to be stalled) and
before they change anything, the revision included (the writer's gate), and a background thread
reconciles. It reads the store's write id: if the store still holds the last
confirmed one, a fence (a new id) voids whatever is in flight; if the refused update got there
first, the dataset is rewritten from the KB. Then store and KB agree and commits flow again.
"""

from __future__ import annotations

import logging
import threading
import time
import uuid
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rdflib import Literal

from kb.errors import OutcomeUnknown, StoreUnavailable
from kb.models import Delta, Model
from kb.sparqlstore import mirrortext, text
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.query import StoreQueries
from kb.terms import Triple
from kb.writer import Commit, Writer

if TYPE_CHECKING:
    from kb.kb import KB

log = logging.getLogger(__name__)

#: Seconds a whole-dataset rewrite may take at least (a large KB is many triples to send).
REWRITE_TIMEOUT = 120.0


@dataclass(frozen=True)
class MirrorStatus:
    """Whether the store is known to equal the KB; if not, since when (epoch seconds) and why."""

    in_sync: bool
    refused: int  # writes refused because of the store, since the mirror was attached
    since: float | None = None
    error: str | None = None


class SparqlMirror:
    """Keeps one dataset of a SPARQL store equal to a KB (asserted and inferred graphs)."""

    def __init__(self, endpoint: SparqlEndpoint, *, retry: float = 0.2) -> None:
        """``retry``: seconds between two reconciliation attempts while in doubt (doubling up
        to 2 s while the store stays away)."""
        self.endpoint = endpoint
        self.layout = endpoint.layout
        self._queries = StoreQueries(endpoint)
        self._writer: Writer | None = None
        self._unregister: Callable[[], None] | None = None
        self._retry = retry
        self._known_models: set[str] = set()
        self._token: str | None = None  # the write id the store last confirmed
        self._synced_revision = -1  # the KB's revision the store last confirmed
        self._doubt: tuple[float | None, str] | None = (None, "not attached")  # since, last error
        self._sent: dict[str, int] = {}  # while in doubt: ids sent that mean "equal to revision N"
        self._refused = 0
        self._reconciling = threading.Lock()
        self._wake = threading.Event()
        self._closed = threading.Event()
        self._thread: threading.Thread | None = None

    @property
    def stale(self) -> bool:
        """True when the store may differ from the KB (until the mirror has reconciled it)."""
        return self._doubt is not None

    def status(self) -> MirrorStatus:
        doubt = self._doubt
        if doubt is None:
            return MirrorStatus(True, self._refused)
        return MirrorStatus(False, self._refused, *doubt)

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
            stored = set(self._queries.triples(self._queries.graphs(model), inferred=False,
                                               timeout=self._rewrite_timeout()))
            with writer.lock:
                current = writer.models.get(model)
                have = set(current.asserted) if current is not None else set()
                writer.restore(model, sorted(stored - have, key=str), sorted(have - stored, key=str), [],
                               revision=meta.revision)
        return meta.revision

    def attach(self, kb: KB) -> None:
        """Rewrite the dataset from the KB, whatever it held, then mirror every commit."""
        writer = kb.writer
        with writer.lock:
            self._writer = writer
            try:
                write = _new_id()
                update = self._rewrite(None, write, self.stored_models())
                self.endpoint.update(update, self._rewrite_timeout())
            except StoreUnavailable:
                self._writer = None  # not attached: the caller gives up or tries again
                raise
            self._synced(write)
            unregister = writer.on_commit(self._on_commit, durable=True)
            ungate = writer.gate(self._refuse_in_doubt)

            def detached() -> None:
                unregister()
                ungate()

            self._unregister = detached

    def detach(self) -> None:
        if self._unregister is not None:
            self._unregister()
        self._closed.set()
        self._wake.set()
        if self._thread is not None:
            self._thread.join(timeout=5.0)
            self._thread = None
        self._unregister, self._writer = None, None

    # --- commits (under the KB lock) ------------------------------------------------------

    def _refuse_in_doubt(self) -> None:
        """The writer's gate: while in doubt a write is refused before it changes anything, the
        revision included, so reconciliation, which makes the store equal to the KB at one
        revision, is not outrun by writes that are refused anyway."""
        doubt = self._doubt
        if doubt is not None:
            self._refused += 1
            raise StoreUnavailable(
                f"the SPARQL store at {self.endpoint.spec.update_url} is being reconciled after a write "
                f"whose outcome is unknown ({doubt[1]}); nothing was written, retry shortly")

    def _on_commit(self, commit: Commit) -> None:
        writer = self._require_writer()
        self._refuse_in_doubt()  # the gate's check, for a commit that got past it meanwhile
        write = _new_id()
        if commit.cleared is not None or commit.revision != self._synced_revision + 1:
            # The KB moved without the store (a clear, or an undone batch another listener had
            # taken): this commit carries the whole state.
            update = self._rewrite(self._require_token(), write, self._known_models)
        else:
            update = self._change(writer, commit, write)
        self._send(update, None)
        self._synced(write)

    def _change(self, writer: Writer, commit: Commit, write: str) -> str:
        delete: list[str] = []
        insert: list[str] = []
        new_models: list[str] = []
        for delta in commit.deltas:
            model = writer.models.get(delta.model)
            if model is None:
                continue
            if model.name in self._known_models:
                removals, additions = self._delta(model, delta)
                delete.extend(removals)
                insert.extend(additions)
            else:  # a new model starts from the default ontology, not only from this batch
                new_models.append(model.name)
                insert.extend(self._whole(model))
        return mirrortext.change(self.layout, self._require_token(), write, commit.revision, delete, insert,
                                 new_models)

    def _rewrite(self, after: str | None, write: str, stored: Iterable[str]) -> str:
        """The whole dataset from the KB (call under the KB lock)."""
        writer = self._require_writer()
        models = [m for n in writer.models.names if (m := writer.models.get(n)) is not None]
        graphs = [g for model in models for g in self._whole(model)]
        return mirrortext.rewrite(self.layout, after, write, {*stored, *(m.name for m in models)}, graphs,
                                  writer.revision, [m.name for m in models])

    def _whole(self, model: Model) -> list[str]:
        inferred = (t for t in model.closure if t not in model.asserted)
        return [text.graph_data(self.layout.asserted(model.name), model.asserted),
                text.graph_data(self.layout.inferred(model.name), inferred)]

    def _delta(self, model: Model, delta: Delta) -> tuple[list[str], list[str]]:
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
        return ([text.graph_data(asserted_g, asserted_removed), text.graph_data(inferred_g, inferred_out)],
                [text.graph_data(asserted_g, asserted_added), text.graph_data(inferred_g, inferred_in)])

    def _send(self, update: str, timeout: float | None) -> None:
        try:
            self.endpoint.update(update, timeout)
        except OutcomeUnknown as exc:
            self._refused += 1
            self._enter_doubt(str(exc))
            raise
        except StoreUnavailable:
            self._refused += 1  # the store refused it whole: it still holds the confirmed state
            raise

    def _synced(self, write: str) -> None:
        """The store holds ``write``, equal to the KB now (call under the KB lock)."""
        writer = self._require_writer()
        self._token, self._synced_revision = write, writer.revision
        self._known_models = set(writer.models.names)
        self._sent.clear()
        self._doubt = None

    # --- reconciliation (in the background, never waiting on the store under the KB lock) -

    def _enter_doubt(self, error: str) -> None:
        if self._doubt is None:
            self._doubt = (time.time(), error)
            log.warning("the store may hold a write the writer refused (%s): reconciling", error)
        if self._thread is None and not self._closed.is_set():
            self._thread = threading.Thread(target=self._reconcile_loop, name="kb-mirror-reconcile",
                                            daemon=True)
            self._thread.start()
        self._wake.set()

    def _reconcile_loop(self) -> None:
        delay = self._retry
        while not self._closed.is_set():
            self._wake.wait(None if self._doubt is None else delay)  # idle while in sync
            self._wake.clear()
            if self._closed.is_set():
                return
            if self._doubt is None:
                delay = self._retry
                continue
            delay = self._retry if self.reconcile() else min(2.0, delay * 2)

    def reconcile(self) -> bool:
        """One attempt to make the store equal to the KB again; True when it does (or did)."""
        with self._reconciling:
            if self._doubt is None:
                return True
            try:
                return self._reconcile_once()
            except StoreUnavailable as exc:
                doubt = self._doubt
                if doubt is not None:
                    self._doubt = (doubt[0], str(exc))
                return False

    def _reconcile_once(self) -> bool:
        writer = self._require_writer()
        seen, stored = self._store_state()
        if self._adopt(seen):
            return True
        write = _new_id()
        with writer.lock:
            revision = writer.revision
            if seen is not None and seen == self._token and revision == self._synced_revision:
                update, timeout = mirrortext.fence(self.layout, seen, write), None
            else:  # the refused update (or someone else's) got there, or the KB moved: rewrite
                update = self._rewrite(seen, write, stored)
                timeout = self._rewrite_timeout()
            self._sent[write] = revision
        self.endpoint.update(update, timeout)
        seen, _ = self._store_state()
        return self._adopt(seen)

    def _adopt(self, seen: str | None) -> bool:
        """In sync if the store holds an id this reconciliation sent for the KB's revision."""
        writer = self._require_writer()
        with writer.lock:
            if seen is None or self._sent.get(seen) != writer.revision:
                return False
            self._synced(seen)
        log.info("the store is reconciled with the KB at revision %d", self._synced_revision)
        return True

    def _store_state(self) -> tuple[str | None, set[str]]:
        write: str | None = None
        models: set[str] = set()
        for row in self.endpoint.select(mirrortext.state_text(self.layout)):
            if isinstance(row.get("w"), Literal):
                write = str(row["w"])
            if "m" in row:
                models.add(str(row["m"]))
        return write, models

    def _rewrite_timeout(self) -> float:
        return max(REWRITE_TIMEOUT, self.endpoint.timeout)

    def _require_token(self) -> str:
        if self._token is None:
            raise RuntimeError("the mirror is not attached to a KB")
        return self._token

    def _require_writer(self) -> Writer:
        if self._writer is None:
            raise RuntimeError("the mirror is not attached to a KB")
        return self._writer


def _new_id() -> str:
    return uuid.uuid4().hex
