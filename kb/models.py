"""Models ("minds"): each keeps its asserted triples apart from its materialised closure.

One model per agent, as in knowledge_core (kb-compat §2); the robot's own is ``default``. A new
model starts from the default TBox (K15). A batch is applied to one model as one unit: asserted
changes, reasoning and the resulting closure delta, so readers holding the KB lock never see
half of it.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from itertools import chain
from typing import Any

from kb.errors import ReasoningTooLarge
from kb.index import Interner, TripleIndex
from kb.reasonbudget import StepBudget
from kb.reasoner import Reasoner
from kb.tbox import CompiledTBox, compile_tbox, is_schema_triple
from kb.tboxbudget import TBoxBounds
from kb.terms import Node, Triple

DEFAULT_MODEL = "default"
ALL_MODELS = "all"


@dataclass
class Delta:
    """What one batch changed in a model: asserted triples and closure triples."""

    model: str
    asserted_added: list[Triple] = field(default_factory=list)
    asserted_removed: list[Triple] = field(default_factory=list)
    added: list[Triple] = field(default_factory=list)
    removed: list[Triple] = field(default_factory=list)

    def __bool__(self) -> bool:
        return bool(self.added or self.removed or self.asserted_added or self.asserted_removed)


class Model:
    """One named graph pair: asserted triples and their materialised closure."""

    __slots__ = ("asserted", "closure", "name", "reasoner", "tbox_revision")

    def __init__(self, name: str, triples: Iterable[Triple] = (), interner: Interner | None = None) -> None:
        self.name = name
        interner = interner if interner is not None else Interner()
        self.asserted = TripleIndex(interner, by_object=False)
        self.closure = TripleIndex(interner)
        for t in triples:
            self.asserted.add(*t)
        self.reasoner = Reasoner(compile_tbox(self.asserted), self.asserted, self.closure)
        self.reasoner.materialise()
        self.tbox_revision = 0

    @property
    def tbox(self) -> CompiledTBox:
        return self.reasoner.tbox

    def plan_tbox(self, add: Sequence[Triple], remove: Sequence[Triple],
                  bounds: TBoxBounds) -> CompiledTBox | None:
        """The TBox this model would have after ``apply(add, remove)``, compiled within ``bounds``
        (``TBoxTooLarge`` past them, nothing changed); None when the change holds no schema
        triple (the TBox stays)."""
        schema_add = [t for t in add if is_schema_triple(t)]
        schema_remove = {t for t in remove if is_schema_triple(t)}
        if not schema_add and not schema_remove:
            return None
        bounds.check_triples(len(schema_add) + len(schema_remove), self.name)
        kept = (t for t in self.asserted if t not in schema_remove and is_schema_triple(t))
        return compile_tbox(chain(kept, schema_add), bounds)

    def apply(self, add: Sequence[Triple], remove: Sequence[Triple],
              tbox: CompiledTBox | None = None, budget: StepBudget | None = None) -> Delta:
        """Retract then assert; reason incrementally within the ``budget``'s steps (past them,
        ``ReasoningTooLarge`` with the model as it was), or recompile when the TBox changes (to
        ``tbox`` when ``plan_tbox`` made it for this very change)."""
        delta = Delta(self.name)
        asserted = self.asserted
        # The KB's own term objects from here on: every later lookup stops at the identity check
        # (rdflib compares terms in Python code, and a batch's terms are looked up many times).
        interner = asserted.interner
        canonical, intern = interner.canonical, interner.triple
        remove = [(canonical(s), canonical(p), canonical(o)) for s, p, o in remove]
        add = [intern(t) for t in add]
        delta.asserted_removed = [t for t in remove if asserted.remove(*t)]
        delta.asserted_added = [t for t in add if asserted.insert(*t)]
        if not delta.asserted_added and not delta.asserted_removed:
            return delta
        changed = delta.asserted_added + delta.asserted_removed
        if any(is_schema_triple(t) for t in changed):
            self._recompile(delta, tbox)
            return delta
        try:
            removed, readded = self.reasoner.delete(delta.asserted_removed, budget)
            try:
                added = self.reasoner.insert(delta.asserted_added, budget)
            except ReasoningTooLarge:
                for t in readded:
                    self.closure.remove(*t)
                for t in removed:
                    self.closure.insert(*t)
                raise
        except ReasoningTooLarge:
            for t in delta.asserted_added:
                asserted.remove(*t)
            for t in delta.asserted_removed:
                asserted.insert(*t)
            raise
        # A fact removed by DRed and derived again by the additions is no change at all.
        if removed and added:
            gone, new = set(removed), set(added)
            delta.removed = [t for t in removed if t not in new]
            delta.added = readded + [t for t in added if t not in gone]
        else:
            delta.removed = removed
            delta.added = readded + added
        return delta

    def _recompile(self, delta: Delta, tbox: CompiledTBox | None) -> None:
        before = set(self.closure)
        tbox = tbox if tbox is not None else compile_tbox(self.asserted)
        self.reasoner = Reasoner(tbox, self.asserted, self.closure)
        self.reasoner.materialise()
        self.tbox_revision += 1
        after = set(self.closure)
        delta.added = list(after - before)
        delta.removed = list(before - after)

    def is_asserted(self, triple: Triple) -> bool:
        return triple in self.asserted


class Models:
    """The set of models, created on first use from the default TBox."""

    def __init__(self, default_triples: Sequence[Triple]) -> None:
        self._defaults = list(default_triples)
        self._interner = Interner()
        self._models: dict[str, Model] = {DEFAULT_MODEL: Model(DEFAULT_MODEL, self._defaults, self._interner)}

    @property
    def shorts(self) -> dict[Node, Any]:
        """The output forms of terms answers named, cached with the terms (see ``render``)."""
        return self._interner.shorts

    @property
    def defaults(self) -> list[Triple]:
        return self._defaults

    @property
    def names(self) -> list[str]:
        return list(self._models)

    @property
    def default(self) -> Model:
        return self._models[DEFAULT_MODEL]

    def get(self, name: str) -> Model | None:
        return self._models.get(name)

    def create(self, name: str) -> Model:
        model = self._models.get(name)
        if model is None:
            model = self._models[name] = Model(name, self._defaults, self._interner)
        return model

    def drop(self, name: str) -> None:
        """Forget a model (undoing the batch that created it); the default model stays."""
        if name != DEFAULT_MODEL:
            self._models.pop(name, None)

    def prune_terms(self) -> None:
        """Forget interned terms no model uses any more (cheap unless many were dropped)."""
        indexes = [ix for m in self._models.values() for ix in (m.asserted, m.closure)]
        self._interner.prune_if_large(indexes)

    def reset(self, keep_defaults: bool) -> ModelsState:
        """Start over with only the default model; returns what ``restore`` puts back."""
        saved = ModelsState(self._interner, self._models)
        defaults = self._defaults if keep_defaults else []
        self._interner = Interner()
        self._models = {DEFAULT_MODEL: Model(DEFAULT_MODEL, defaults, self._interner)}
        return saved

    def restore(self, saved: ModelsState) -> None:
        """Put back the models a ``reset`` replaced (its change was refused)."""
        self._interner, self._models = saved.interner, saved.models


@dataclass(frozen=True)
class ModelsState:
    """The models and their interner as they were before a ``reset``."""

    interner: Interner
    models: dict[str, Model]
