"""Where a fact learnt from dialogue came from: RDF reification in the robot's model.

Each adopted fact gets one record, `told_<digest>` (the digest of the fact, so telling it again
replaces its record rather than adding one):

    told_1a2b… rdf:type ToldFact ; rdf:subject mug_red ; rdf:predicate belongsTo ;
               rdf:object person_bob ; toldBy person_bob ;
               toldAt "2025-06-01T10:00:00+00:00"^^xsd:dateTime ; toldAs "the red mug is mine"

Reification rather than a named graph: the record lives beside the fact in the robot's model, so a
plain `find` answers "who told you that, and when" (and the journal, the SPARQL store mirror and
read replicas carry it like any other fact), while each person's own model (knowledge_core's
per-agent models) stays what that person believes. A fact asserted in the robot's model without
a record came from perception (or another producer), and dialogue never overwrites it.
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable
from dataclasses import dataclass
from datetime import UTC, datetime

from rdflib import RDF, XSD, Literal, URIRef

from kb.protocol import KnowledgeBase
from kb.terms import ORO, Node, format_term, format_triple, parse_name
from kb.unicode import carried

TOLD_FACT = URIRef(ORO + "ToldFact")
TOLD_BY = URIRef(ORO + "toldBy")
TOLD_AT = URIRef(ORO + "toldAt")
TOLD_AS = URIRef(ORO + "toldAs")
#: Longest words kept with a record (characters).
MAX_WORDS = 300

Fact = tuple[URIRef, URIRef, Node]


def record_of(fact: Fact) -> URIRef:
    """The id of a fact's record: the same fact always has the same record."""
    digest = hashlib.sha256("\x1f".join(str(t) for t in fact).encode()).hexdigest()[:16]
    return URIRef(ORO + f"told_{digest}")


def record(fact: Fact, speaker: URIRef, when: datetime, words: str) -> list[str]:
    """The statements of a fact's record (statement syntax, written from terms)."""
    node = record_of(fact)
    subject, predicate, obj = fact
    stamp = Literal(when.astimezone(UTC).isoformat(timespec="seconds"), datatype=XSD.dateTime)
    triples: list[tuple[Node, Node, Node]] = [
        (node, RDF.type, TOLD_FACT), (node, RDF.subject, subject), (node, RDF.predicate, predicate),
        (node, RDF.object, obj), (node, TOLD_BY, speaker), (node, TOLD_AT, stamp),
    ]  # fmt: skip
    if words.strip():
        triples.append((node, TOLD_AS, Literal(carried(words).strip()[:MAX_WORDS])))
    return [format_triple(t) for t in triples]


def forget(kb: KnowledgeBase, fact: Fact) -> list[str]:
    """The statements of a fact's record as the KB holds them now (to retract with the fact)."""
    node = record_of(fact)
    out = []
    for row in kb.find([f"{format_term(node)} ?p ?o"]):
        predicate = parse_name(str(row["p"]), "predicate")
        value = row["o"]
        term: Node
        if predicate == RDF.object:
            term = fact[2]
        elif predicate == TOLD_AT:
            term = Literal(str(value), datatype=XSD.dateTime)
        elif predicate == TOLD_AS:
            term = Literal(str(value))
        else:
            term = parse_name(str(value), "value")
        out.append(format_triple((node, predicate, term)))
    return out


@dataclass(frozen=True)
class Told:
    """One adopted fact and who told it when (`find` output forms: ids, and the value as given)."""

    record: str
    subject: str
    predicate: str
    object: object
    by: str
    at: str
    words: str = ""


def told(kb: KnowledgeBase, subject: str | None = None, by: str | None = None) -> list[Told]:
    """The facts learnt from dialogue (about `subject`, or told by `by`), oldest first."""
    s = format_term(parse_name(subject, "subject")) if subject is not None else "?s"
    who = format_term(parse_name(by, "speaker")) if by is not None else "?by"
    rows = kb.find([f"?r rdf:type {format_term(TOLD_FACT)}", f"?r rdf:subject {s}", "?r rdf:predicate ?p",
                    "?r rdf:object ?o", f"?r toldBy {who}", "?r toldAt ?at"])
    words = {str(r["r"]): str(r["w"]) for r in kb.find(["?r toldAs ?w", f"?r rdf:subject {s}"])}
    out = [Told(str(r["r"]), subject or str(r["s"]), str(r["p"]), r["o"], by or str(r["by"]), str(r["at"]),
                words.get(str(r["r"]), "")) for r in rows]
    return sorted(out, key=lambda t: (t.at, t.record))


def teller(kb: KnowledgeBase, fact: Fact) -> str | None:
    """Who told a fact the robot adopted (the record's `toldBy`), or None: not told (perceived)."""
    rows = kb.find([f"{format_term(record_of(fact))} toldBy ?who"])
    return str(rows[0]["who"]) if rows else None


def recorded(kb: KnowledgeBase, facts: Iterable[Fact]) -> set[Fact]:
    """Which of `facts` have a record (were told), the others being perception's."""
    return {f for f in facts if kb.exist([f"{format_term(record_of(f))} rdf:type {format_term(TOLD_FACT)}"])}
