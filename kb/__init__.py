"""situated's knowledge base: a knowledge_core-compatible OWL/RDF KB with incremental reasoning.

``from kb import KB; kb = KB()`` gives a ready KB with the default ORO-compatible ontology;
``RemoteKB`` is the same API over a SPARQL 1.1 store (a read replica of a writer). Both implement
``KnowledgeBase`` (the protocol code should type against) through ``Facade`` (the shared argument
checks), and every error they raise is a ``KbError`` (``kb.errors``).
"""

from kb.errors import (
    DataCorrupt,
    InvalidCharacter,
    InvalidRegex,
    InvalidSparql,
    InvalidUnicode,
    KbError,
    ModelLimit,
    NotSerialisable,
    OutcomeUnknown,
    QueryEvaluationError,
    QueryTimeout,
    QueryTooLarge,
    ReasoningTooLarge,
    StorageError,
    StorageFull,
    StoreUnavailable,
    TBoxTooLarge,
    TooManyRows,
    UnsupportedUpdate,
)
from kb.facade import Facade
from kb.kb import KB
from kb.protocol import KnowledgeBase
from kb.sparqlstore.remote import RemoteKB
from kb.sugar import __version__

__all__ = [
    "KB",
    "DataCorrupt",
    "Facade",
    "InvalidCharacter",
    "InvalidRegex",
    "InvalidSparql",
    "InvalidUnicode",
    "KbError",
    "KnowledgeBase",
    "ModelLimit",
    "NotSerialisable",
    "OutcomeUnknown",
    "QueryEvaluationError",
    "QueryTimeout",
    "QueryTooLarge",
    "ReasoningTooLarge",
    "RemoteKB",
    "StorageError",
    "StorageFull",
    "StoreUnavailable",
    "TBoxTooLarge",
    "TooManyRows",
    "UnsupportedUpdate",
    "__version__",
]
