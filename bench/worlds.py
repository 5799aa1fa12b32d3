"""Synthetic robot worlds for the benchmarks (the workloads of kb-compat §8.1).

Deterministic for a given size and seed, written as KB statements so every benchmark goes
through the same parsing and write path as a client would.
"""

from __future__ import annotations

import random
from collections.abc import Iterator
from dataclasses import dataclass

COLOURS = ["black", "blue", "gray", "green", "orange", "pink", "red", "violet", "white", "yellow"]
# dbr:Cup is about 2 % of the objects, as in the reference query workload.
CLASSES = ["dbr:Cup"] + [f"Thing_class_{i}" for i in range(49)]


@dataclass(frozen=True)
class QueryWorld:
    """n statements: n/6 objects (type, label, room, colour), humans each seeing some objects
    (by default n/100 humans seeing 20 each, 2 % of the objects cups), the robot seeing the rest
    as filler. ``cups``, ``humans`` and ``sightings`` make the grounding query's answer larger
    (issue 18's world: 9 % cups, 40 humans seeing 25 objects each)."""

    size: int
    seed: int = 1
    cups: float = 0.0
    humans: int = 0
    sightings: int = 20

    def statements(self) -> Iterator[str]:
        rng = random.Random(self.seed)
        n_objects = self.size // 6
        n_humans = self.humans or max(1, self.size // 100)
        rooms = [f"room_{i}" for i in range(max(2, n_objects // 200))]
        emitted = 0
        for i in range(n_objects):
            obj = f"obj_{i}"
            kind = "dbr:Cup" if self.cups and rng.random() < self.cups else rng.choice(self._classes)
            yield f"{obj} rdf:type {kind}"
            yield f'{obj} rdfs:label "object {i}"'
            yield f"{obj} isIn {rng.choice(rooms)}"
            yield f"{obj} hasColor {rng.choice(COLOURS)}"
            emitted += 4
        for h in range(n_humans):
            yield f"human_{h} rdf:type Human"
            emitted += 1
            for _ in range(self.sightings):
                yield f"human_{h} sees obj_{rng.randrange(n_objects)}"
                emitted += 1
        yield "myself rdf:type Robot"
        emitted += 1
        while emitted < self.size:
            yield f"myself sees obj_{rng.randrange(n_objects)}"
            emitted += 1

    @property
    def _classes(self) -> list[str]:
        # With an explicit share of cups, the other objects are of the 49 other classes.
        return CLASSES[1:] if self.cups else CLASSES


QUERY = ["?h sees ?o", "?o rdf:type dbr:Cup", "?h rdf:type Human"]
SPARQL_QUERY = "SELECT ?h ?o WHERE { ?h :sees ?o . ?o rdf:type dbr:Cup . ?h rdf:type :Human }"


@dataclass(frozen=True)
class PerceptionWorld:
    """Agents, rooms and objects with types, labels, isIn/isOn, sees/looksAt and holds: the
    ontology workload, on the real ORO-compatible ontology."""

    objects: int
    agents: int = 20
    seed: int = 2

    def statements(self) -> Iterator[str]:
        rng = random.Random(self.seed)
        kinds = ["dbr:Cup", "dbr:Book", "dbr:Apple", "dbr:Smartphone", "dbr:Pear", "dbr:Bottle"]
        furniture = ["dbr:Table_(furniture)", "dbr:Shelf_(storage)", "dbr:Couch", "dbr:Coffee_table"]
        rooms = [f"zone_{i}" for i in range(10)]
        for room in rooms:
            yield f"{room} rdf:type ZoneOfInterest"
            yield f'{room} rdfs:label "{room.replace("_", " ")}"'
        supports = [f"furniture_{i}" for i in range(max(4, self.objects // 20))]
        for f in supports:
            yield f"{f} rdf:type {rng.choice(furniture)}"
            yield f"{f} isIn {rng.choice(rooms)}"
        for i in range(self.objects):
            yield f"thing_{i} rdf:type {rng.choice(kinds)}"
            yield f'thing_{i} rdfs:label "thing {i}"'
            yield f"thing_{i} isIn {rng.choice(rooms)}"
            if rng.random() < 0.2:
                yield f"thing_{i} isOn {rng.choice(supports)}"
        for a in range(self.agents):
            yield f"person_{a} rdf:type Human"
            for _ in range(10):
                yield f"person_{a} sees thing_{rng.randrange(self.objects)}"
            yield f"person_{a} looksAt thing_{rng.randrange(self.objects)}"
            yield f"person_{a} holds thing_{rng.randrange(self.objects)}"
        yield "myself rdf:type Robot"

    def ticks(self, count: int) -> Iterator[tuple[list[str], list[str]]]:
        """(add 3, retract the 3 of three ticks ago): looksAt, isIn and holds, as perception does."""
        rng = random.Random(self.seed + 1)
        window: list[list[str]] = []
        for _ in range(count):
            a = rng.randrange(self.agents)
            add = [
                f"person_{a} looksAt thing_{rng.randrange(self.objects)}",
                f"thing_{rng.randrange(self.objects)} isIn zone_{rng.randrange(10)}",
                f"person_{a} holds thing_{rng.randrange(self.objects)}",
            ]
            window.append(add)
            remove = window.pop(0) if len(window) > 3 else []
            yield add, remove
