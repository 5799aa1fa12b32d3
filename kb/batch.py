"""A batch: the validated ground changes of one write, and the rules that hold within one.

Within a batch a later value of a functional property replaces an earlier one (kb-compat §3.5),
and an activation (``x rdf:type ActiveConcept``) lives ``ACTIVE_CONCEPT_LIFESPAN`` seconds
whatever lifespan the batch gives the rest.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from rdflib import URIRef
from rdflib.namespace import RDF

from kb.terms import ORO, Triple

ACTIVE_CONCEPT = URIRef(ORO + "ActiveConcept")
ACTIVE_CONCEPT_LIFESPAN = 5.0


@dataclass
class Batch:
    """Validated ground changes for some models; applying it cannot fail."""

    models: Sequence[str]
    add: list[Triple] = field(default_factory=list)
    remove: list[Triple] = field(default_factory=list)
    lifespan: float = 0.0
    replace_functional: bool = True
    # Changes specific to one model, besides those of every model above: pattern retraction
    # matches per model, and one write may tell each model its own (a belief and its adoption).
    add_by_model: dict[str, list[Triple]] = field(default_factory=dict)
    remove_by_model: dict[str, list[Triple]] = field(default_factory=dict)

    @property
    def size(self) -> int:
        """How many statements it names (a bulk change pauses the garbage collector)."""
        by_model = (*self.add_by_model.values(), *self.remove_by_model.values())
        return len(self.add) + len(self.remove) + sum(map(len, by_model))

    def lifespan_of(self, triple: Triple) -> float:
        """Seconds an added triple lives (0: for ever)."""
        return ACTIVE_CONCEPT_LIFESPAN if is_activation(triple) else self.lifespan


def is_activation(triple: Triple) -> bool:
    # str's own == first: rdflib's is Python code, and this runs for every statement written.
    _s, p, o = triple
    return _same_text(o, ACTIVE_CONCEPT) is True and p == RDF.type and o == ACTIVE_CONCEPT


_same_text = str.__eq__


def last_functional_wins(add: Sequence[Triple], functional: frozenset[Any]) -> list[Triple]:
    """Within one batch, a later value of a functional property replaces an earlier one."""
    if not functional:
        return list(add)
    last: dict[tuple[Any, Any], Triple] = {}
    for t in add:
        if t[1] in functional:
            last[(t[0], t[1])] = t
    return [t for t in add if t[1] not in functional or last[(t[0], t[1])] == t]
