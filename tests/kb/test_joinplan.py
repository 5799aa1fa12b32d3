"""The join's first step: chosen by what it costs with the step after it, not by its count alone."""

from __future__ import annotations

from collections.abc import Iterator

from rdflib import URIRef, Variable

from kb.index import TripleIndex
from kb.joinplan import JoinIndex, cheapest, survey
from kb.query import _compile, _variables, build_query, rows
from kb.terms import Node, Pattern

ORO = "http://kb.openrobots.org#"


def o(name: str) -> URIRef:
    return URIRef(ORO + name)


def watchers_world() -> TripleIndex:
    """10 humans who each see 100 things, and 50 cups each seen by the robot alone, but cup_0
    seen by human_0 too: fewer humans than cups, yet starting from the cups is the cheap way."""
    index = TripleIndex()
    for h in range(10):
        index.add(o(f"human_{h}"), o("type"), o("Human"))
        for t in range(100):
            index.add(o(f"human_{h}"), o("sees"), o(f"thing_{h}_{t}"))
    for c in range(50):
        index.add(o(f"cup_{c}"), o("type"), o("Cup"))
        index.add(o("robot"), o("sees"), o(f"cup_{c}"))
    index.add(o("human_0"), o("sees"), o("cup_0"))
    return index


def patterns(*texts: tuple[str, str, str]) -> list[Pattern]:
    return [tuple(Variable(t[1:]) if t.startswith("?") else o(t) for t in text) for text in texts]  # type: ignore[misc]


QUERY = patterns(("?h", "sees", "?o"), ("?o", "type", "Cup"), ("?h", "type", "Human"))


class Reads:
    """A JoinIndex that counts the triples the join reads through ``scan``."""

    def __init__(self, index: TripleIndex) -> None:
        self.index, self.scanned = index, 0

    def __contains__(self, triple: tuple[Node, Node, Node]) -> bool:
        return triple in self.index

    def canonical(self, term: Node) -> Node:
        return self.index.canonical(term)

    def count(self, s: Node | None, p: Node | None, o: Node | None) -> int:
        return self.index.count(s, p, o)

    def scan(self, s: Node | None, p: Node | None, o: Node | None) -> Iterator[tuple[Node, Node, Node]]:
        for triple in self.index.scan(s, p, o):
            self.scanned += 1
            yield triple


def first_choice(index: JoinIndex, query: list[Pattern]) -> Pattern:
    compiled = _compile(index, query, _variables(query))
    binding: list[Node | None] = [None] * len(_variables(query))
    surveyed = survey(index, compiled, binding)
    assert surveyed is not None
    return query[cheapest(index, *surveyed, binding)]


def test_the_fewest_matches_are_not_chosen_when_each_leads_to_many() -> None:
    index = watchers_world()
    assert index.count(None, o("type"), o("Human")) < index.count(None, o("type"), o("Cup"))
    assert first_choice(index, QUERY) == QUERY[1]  # the cups: each is seen by one or two agents


def test_the_fewest_matches_are_chosen_when_each_leads_to_few() -> None:
    index = watchers_world()
    query = patterns(("?h", "type", "Human"), ("?h", "sees", "?o"))
    assert first_choice(index, query) == query[0]


def test_the_join_reads_fewer_triples_and_finds_the_same_rows() -> None:
    index = watchers_world()
    query = build_query(QUERY)
    reads = Reads(index)
    found = rows(reads, query)
    assert found == {(o("human_0"), o("cup_0"))}
    # From the humans (the fewest): 10, then the 50 cups for each; from the cups: 50, then
    # the one or two agents that see each (and a few triples read to choose).
    assert reads.scanned < 200


def test_a_closed_pattern_that_fails_ends_the_branch_before_the_next_step() -> None:
    index = watchers_world()
    query = build_query(patterns(("?h", "sees", "?o"), ("?h", "type", "Human"), ("?o", "type", "Cup"),
                                 ("?o", "type", "Book")))
    assert rows(index, query) == set()
