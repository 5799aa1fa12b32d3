"""The persons the KB knows: id, name, whether the robot sees them, engagement level."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from kb.protocol import KnowledgeBase


@dataclass(frozen=True)
class Human:
    id: str
    name: str | None
    seen: bool
    engagement: str | None


def _by_person(rows: Sequence[Any], key: str) -> dict[str, str]:
    found: dict[str, str] = {}
    for row in rows:
        found.setdefault(str(row["p"]), str(row[key]))
    return found


def known_humans(kb: KnowledgeBase) -> list[Human]:
    """Every ``Human`` in the robot's model, sorted by id (one conjunctive query per aspect)."""
    people = sorted({str(row["p"]) for row in kb.find(["?p rdf:type Human"])})
    names = _by_person(kb.find(["?p rdf:type Human", "?p rdfs:label ?name"]), "name")
    seen = {str(row["p"]) for row in kb.find(["?p rdf:type Human", "myself sees ?p"])}
    levels = _by_person(kb.find(["?p rdf:type Human", "?p engagementLevel ?level"]), "level")
    return [Human(p, names.get(p), p in seen, levels.get(p)) for p in people]


def render(humans: Sequence[Human]) -> str:
    if not humans:
        return "no persons known"
    rows = [("id", "name", "seen", "engagement")]
    rows += [(h.id, h.name or "-", "yes" if h.seen else "no", h.engagement or "-") for h in humans]
    widths = [max(len(r[i]) for r in rows) for i in range(4)]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip()
                     for row in rows)
