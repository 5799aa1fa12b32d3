"""How a situated dataset lies in a SPARQL 1.1 store: graph names, bookkeeping, blank nodes.

One store may hold several datasets (one per site or per test). For dataset ``D`` and model
``M`` (model names percent-encoded):

- ``urn:situated:D/asserted/M``: the model's asserted triples;
- ``urn:situated:D/inferred/M``: what the reasoner derived that is not asserted (so the two
  graphs are disjoint and their merge is the model's closure);
- ``urn:situated:D/meta``: ``<urn:situated:D> sit:revision N``, one ``sit:model "M"`` per model and
  ``sit:write "ID"``, the id of the writer's last update (each update applies only where the store
  still holds the id it follows: kb.sparqlstore.mirrortext);
- ``urn:situated:D/dialogues``: dialogue sessions shared by the service processes.

Blank nodes cannot cross SPARQL requests (``INSERT DATA`` mints new ones, ``DELETE DATA`` refuses
them), so they are stored as skolem IRIs under ``/.well-known/genid/`` (RDF 1.1 §3.5) and turned
back into the same blank nodes when read.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Final
from urllib.parse import quote, unquote

from rdflib import BNode, URIRef

from kb.errors import KbError

SIT: Final = "urn:situated:vocab#"
REVISION: Final = URIRef(SIT + "revision")
MODEL: Final = URIRef(SIT + "model")
WRITE: Final = URIRef(SIT + "write")
GENID: Final = "urn:situated:/.well-known/genid/"
_DATASET = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.\-]{0,63}")


@dataclass(frozen=True)
class Layout:
    """The graph IRIs of one dataset."""

    dataset: str = "situated"

    def __post_init__(self) -> None:
        if not _DATASET.fullmatch(self.dataset):
            raise KbError(f"dataset name {self.dataset!r} must be 1-64 letters, digits, '_', '.' or '-'")

    @property
    def root(self) -> URIRef:
        return URIRef(f"urn:situated:{self.dataset}")

    def asserted(self, model: str) -> URIRef:
        return self._named("asserted", model)

    def inferred(self, model: str) -> URIRef:
        return self._named("inferred", model)

    def graphs(self, model: str) -> tuple[URIRef, URIRef]:
        """The asserted and inferred graphs: their merge is the model's closure."""
        return self.asserted(model), self.inferred(model)

    @property
    def meta(self) -> URIRef:
        return URIRef(f"urn:situated:{self.dataset}/meta")

    @property
    def dialogues(self) -> URIRef:
        return URIRef(f"urn:situated:{self.dataset}/dialogues")

    def dialogue(self, dialogue_id: str) -> URIRef:
        return self._named("dialogue", dialogue_id)

    def _named(self, kind: str, name: str) -> URIRef:
        return URIRef(f"urn:situated:{self.dataset}/{kind}/{quote(name, safe='')}")

    def model_of(self, graph: str) -> str | None:
        """The model an asserted or inferred graph belongs to, else None."""
        for kind in ("asserted", "inferred"):
            prefix = f"urn:situated:{self.dataset}/{kind}/"
            if graph.startswith(prefix):
                return unquote(graph[len(prefix):])
        return None


def skolem(node: BNode) -> URIRef:
    return URIRef(GENID + quote(str(node), safe=""))


def unskolem(iri: str) -> URIRef | BNode:
    """A skolem IRI back to its blank node; any other IRI as it is."""
    if iri.startswith(GENID):
        return BNode(unquote(iri[len(GENID):]))
    return URIRef(iri)
