"""Which pattern a join starts from, and which patterns a step leaves to check.

The fewest matches is not always the cheapest start: in ``?h sees ?o . ?o rdf:type dbr:Cup .
?h rdf:type Human`` there are fewer humans than cups, but each human sees dozens of things and
each cup is seen by a couple of agents, so starting from the cups visits a third of the rows.
At the top of a join (one choice per query, where it matters most), each candidate is costed as
its matches times the matches of the step that would follow it, measured on a few of its own
matches with the index's exact counts; below, the join keeps choosing by exact counts alone.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from itertools import islice
from typing import Protocol, cast

from kb.terms import Node

# A compiled pattern: for each position, (constant, -1) or (None, variable slot).
Slot = tuple[Node | None, int]
Compiled = tuple[Slot, Slot, Slot]
# A pattern under the current bindings: each position's term, None where still unbound.
Resolved = tuple[Node | None, Node | None, Node | None]
# A join step once its pattern is chosen: the slots it binds (-1: none) for subject, predicate
# and object; the patterns it closes (checked per match), those left open, and the steps
# below it (shared by every match: the same slots are bound in each).
Step = tuple[int, int, int, list[Compiled], list[Compiled], dict[int, "Step"]]

#: Matches of a candidate first pattern looked at to estimate the step after it.
SAMPLES = 4
#: Index lookups under which the pattern with the fewest matches is joined first unsampled:
#: sampling costs a few dozen, and could not save more than the fewest matches cost at most.
PLAN_FROM = 128


class JoinIndex(Protocol):
    """What the join reads: a ``TripleIndex``, or a ``kb.deadline.TimedIndex`` over one."""

    def __contains__(self, triple: tuple[Node, Node, Node]) -> bool: ...

    def canonical(self, term: Node) -> Node: ...

    def count(self, s: Node | None, p: Node | None, o: Node | None) -> int: ...

    def scan(self, s: Node | None, p: Node | None, o: Node | None) -> Iterator[tuple[Node, Node, Node]]: ...


def resolve(pattern: Compiled, binding: Sequence[Node | None]) -> Resolved:
    (cs, vs), (cp, vp), (co, vo) = pattern
    return (cs if vs < 0 else binding[vs], cp if vp < 0 else binding[vp], co if vo < 0 else binding[vo])


def closed_lookup(index: JoinIndex) -> Callable[[Resolved], bool]:
    """Whether the index holds a resolved pattern, for patterns whose every slot is bound (so
    the ``None`` of ``Resolved`` never reaches the index)."""
    return cast("Callable[[Resolved], bool]", index.__contains__)


def split(patterns: list[Compiled], binding: Sequence[Node | None],
          binds: set[int]) -> tuple[list[Compiled], list[Compiled]]:
    """(checks, rest): the patterns whose every variable is bound once the slots ``binds`` are,
    and the others."""
    checks: list[Compiled] = []
    rest: list[Compiled] = []
    for pattern in patterns:
        (_, a), (_, b), (_, c) = pattern
        if ((a < 0 or a in binds or binding[a] is not None)
                and (b < 0 or b in binds or binding[b] is not None)
                and (c < 0 or c in binds or binding[c] is not None)):
            checks.append(pattern)
        else:
            rest.append(pattern)
    return checks, rest


def plan_step(kept: list[Compiled], i: int, start: Resolved, binding: Sequence[Node | None]) -> Step:
    """The step that joins ``kept[i]``, resolved as ``start`` under ``binding``."""
    (_, vs), (_, vp), (_, vo) = kept[i]
    s, p, o = start
    free_s = vs if s is None else -1
    free_p = vp if p is None else -1
    free_o = vo if o is None else -1
    checks, rest = split(kept[:i] + kept[i + 1:], binding, {free_s, free_p, free_o})
    return free_s, free_p, free_o, checks, rest, {}


def survey(index: JoinIndex, patterns: list[Compiled], binding: Sequence[Node | None]
           ) -> tuple[list[Compiled], list[Resolved], list[int]] | None:
    """The patterns still open under ``binding``, each resolved and with its exact count; None
    when a pattern has no match (the branch ends). A closed pattern that holds binds nothing
    and is left out."""
    count = index.count
    kept: list[Compiled] = []
    found: list[Resolved] = []
    counts: list[int] = []
    for pattern in patterns:
        (cs, vs), (cp, vp), (co, vo) = pattern
        s = cs if vs < 0 else binding[vs]
        p = cp if vp < 0 else binding[vp]
        o = co if vo < 0 else binding[vo]
        n = count(s, p, o)
        if n == 0:
            return None
        if s is None or p is None or o is None:
            kept.append(pattern)
            found.append((s, p, o))
            counts.append(n)
    return kept, found, counts


def cheapest(index: JoinIndex, kept: list[Compiled], found: list[Resolved], counts: list[int],
             binding: list[Node | None]) -> int:
    """The position in ``kept`` of the pattern to join first: the least matches × (2 + the
    matches of the next step per match), each match costing itself and the next step's lookup.
    Candidates are tried by count, and one that would cost more than the best so far even if
    each of its matches led nowhere is not sampled (in a small world, most often none but the
    first)."""
    order = sorted(range(len(kept)), key=counts.__getitem__)
    if counts[order[0]] * (2 + _open_bound(kept, counts, order[0], found[order[0]], binding)) <= PLAN_FROM:
        return order[0]  # the fewest matches cannot cost much: not worth sampling
    best_i, best_cost = -1, 0.0
    for i in order:
        if best_i >= 0 and 2 * counts[i] >= best_cost:
            break
        cost = counts[i] * (2 + _next_step(index, kept, i, found[i], binding))
        if best_i < 0 or cost < best_cost:
            best_i, best_cost = i, cost
    return best_i


def _open_bound(kept: list[Compiled], counts: list[int], i: int, start: Resolved,
                binding: Sequence[Node | None]) -> int:
    """At most how many matches the step after ``kept[i]`` has per match: the fewest matches,
    now, of a pattern it leaves open (binding more only narrows them); 0 when it leaves none."""
    (_, vs), (_, vp), (_, vo) = kept[i]
    s, p, o = start
    binds = (vs if s is None else -1, vp if p is None else -1, vo if o is None else -1)
    fewest = -1
    for j, ((_, a), (_, b), (_, c)) in enumerate(kept):
        if j != i and ((a >= 0 and a not in binds and binding[a] is None)
                       or (b >= 0 and b not in binds and binding[b] is None)
                       or (c >= 0 and c not in binds and binding[c] is None)):
            fewest = counts[j] if fewest < 0 else min(fewest, counts[j])
    return max(fewest, 0)


def _next_step(index: JoinIndex, kept: list[Compiled], i: int, start: Resolved,
               binding: list[Node | None]) -> float:
    """The mean number of matches of the step after ``kept[i]``, over a few of its matches: 0
    where a pattern it closes fails, else the fewest matches of a pattern it leaves open."""
    free = [(position, slot) for position, ((_, slot), term) in enumerate(zip(kept[i], start, strict=True))
            if term is None]
    checks, rest = split(kept[:i] + kept[i + 1:], binding, {slot for _, slot in free})
    if not rest:
        return 0.0  # every other pattern becomes a check: a lookup per match, no step after it
    count, holds = index.count, closed_lookup(index)
    total, looked = 0, 0
    for triple in islice(index.scan(*start), SAMPLES):
        if _bind(free, triple, binding):
            looked += 1
            for check in checks:
                if not holds(resolve(check, binding)):
                    break
            else:
                total += min([count(*resolve(pattern, binding)) for pattern in rest])
        for _, slot in free:
            binding[slot] = None
    return total / looked if looked else 0.0


def _bind(free: list[tuple[int, int]], triple: tuple[Node, Node, Node], binding: list[Node | None]) -> bool:
    """Bind the free slots to the triple's terms; False if a repeated variable disagrees."""
    for position, slot in free:
        value, current = triple[position], binding[slot]
        if current is None:
            binding[slot] = value
        elif current != value:
            return False
    return True
