"""Conjunctive pattern matching over a triple index.

The first step is the pattern whose matches cost least with the step after them
(``kb.joinplan``): ``?h sees ?o . ?o rdf:type dbr:Cup . ?h rdf:type Human`` starts from the cups
when each cup is seen by a couple of agents and each human sees dozens of things, and never
builds the Human × Cup cross product that rdflib's SPARQL engine does (kb-compat §8.5). Below
it, each step joins the pattern with the fewest matches under the bindings made so far (exact
counts from the index), and the patterns a step binds completely are checked on each of its
matches rather than given a level of their own.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from operator import itemgetter

from rdflib import BNode, Variable

from kb.errors import KbError, TooManyRows
from kb.joinplan import Compiled, JoinIndex, Resolved, Slot, Step, cheapest, closed_lookup, plan_step, survey
from kb.terms import Node, Pattern, is_anonymous

Row = tuple[Node, ...]


@dataclass(frozen=True)
class Query:
    """Parsed patterns plus the variables to project, in output order."""

    patterns: tuple[Pattern, ...]
    projection: tuple[Variable, ...]
    names: tuple[str, ...]

    @property
    def ground(self) -> bool:
        return not any(isinstance(t, Variable) for pattern in self.patterns for t in pattern)


def build_query(patterns: Sequence[Pattern], vars: Sequence[str] | None = None) -> Query:
    """Choose the projected variables as knowledge_core does (kb-compat §1.5, §3.2): the named
    variables (those given in ``vars``, else all of the patterns'); anonymous ones (``*``,
    ``?__x``) only when there is no named one, then called ``var1``, ``var2``... in order."""
    seen: list[Variable] = []
    for pattern in patterns:
        for term in pattern:
            if isinstance(term, Variable) and term not in seen:
                seen.append(term)
    chosen = _chosen(seen, vars) if vars else seen
    named = [v for v in chosen if not is_anonymous(v)]
    if named:
        return Query(tuple(patterns), tuple(named), tuple(str(v) for v in named))
    return Query(tuple(patterns), tuple(chosen), tuple(f"var{i}" for i in range(1, len(chosen) + 1)))


def _chosen(seen: list[Variable], vars: Sequence[str]) -> list[Variable]:
    projection: list[Variable] = []
    for name in vars:
        bare = name[1:] if isinstance(name, str) and name.startswith("?") else name
        if not isinstance(bare, str) or not bare.isidentifier():
            raise KbError(f"vars must be variable names such as '?obj', got {name!r}")
        var = Variable(bare)
        if var not in seen:
            raise KbError(f"variable ?{var} of vars does not occur in the patterns")
        projection.append(var)
    return projection


def _compile(index: JoinIndex, patterns: Sequence[Pattern], order: Sequence[Variable]) -> list[Compiled]:
    slots = {v: i for i, v in enumerate(order)}
    compiled: list[Compiled] = []
    for pattern in patterns:
        parts: list[Slot] = []
        for term in pattern:
            if isinstance(term, Variable):
                parts.append((None, slots[term]))
            else:
                parts.append((index.canonical(term), -1))  # the index's own object: fast lookups
        compiled.append((parts[0], parts[1], parts[2]))
    return compiled


def _variables(patterns: Sequence[Pattern]) -> list[Variable]:
    seen: list[Variable] = []
    for pattern in patterns:
        for term in pattern:
            if isinstance(term, Variable) and term not in seen:
                seen.append(term)
    return seen


def solve(index: JoinIndex, patterns: Sequence[Pattern]) -> Iterator[dict[Variable, Node]]:
    """Every binding of the variables that satisfies all patterns (with repetitions)."""
    order = _variables(patterns)
    for values in _solutions(index, patterns, order):
        yield dict(zip(order, values, strict=True))


def _solutions(
    index: JoinIndex, patterns: Sequence[Pattern], order: Sequence[Variable]
) -> Iterator[list[Node]]:
    binding: list[Node | None] = [None] * len(order)
    compiled = _compile(index, patterns, order)
    yield from _solve(index, compiled, binding, closed_lookup(index), {}, plan=True)  # type: ignore[misc]


def _solve(
    index: JoinIndex, patterns: list[Compiled], binding: list[Node | None],
    holds_triple: Callable[[Resolved], bool], steps: dict[int, Step], plan: bool = False,
) -> Iterator[list[Node | None]]:
    # ``steps`` is shared by the calls for one pattern list (a level's every binding): the same
    # slots are bound in each, so what a choice leaves to check and to join is worked out once.
    surveyed = survey(index, patterns, binding)
    if surveyed is None:
        return
    kept, found, counts = surveyed
    if not kept:
        yield binding
        return
    best_i = cheapest(index, kept, found, counts, binding) if plan else counts.index(min(counts))
    step = steps.get(best_i)
    if step is None:
        step = steps[best_i] = plan_step(kept, best_i, found[best_i], binding)
    free_s, free_p, free_o, checks, rest, after = step
    s, p, o = found[best_i]
    for ts, tp, to in index.scan(s, p, o):
        # A variable repeated in one pattern (?x knows ?x) must take one value.
        if free_s >= 0:
            binding[free_s] = ts
        if free_p >= 0:
            if free_p == free_s and tp != ts:
                continue
            binding[free_p] = tp
        if free_o >= 0:
            if (free_o == free_s and to != ts) or (free_o == free_p and to != tp):
                continue
            binding[free_o] = to
        # The patterns this step binds completely are checked here, without a level of their own.
        for (cs, vs), (cp, vp), (co, vo) in checks:
            if not holds_triple((cs if vs < 0 else binding[vs], cp if vp < 0 else binding[vp],
                                 co if vo < 0 else binding[vo])):
                break
        else:
            if rest:
                yield from _solve(index, rest, binding, holds_triple, after)
            else:
                yield binding
    for slot in (free_s, free_p, free_o):
        if slot >= 0:
            binding[slot] = None


def rows(index: JoinIndex, query: Query, limit: int | None = None) -> set[Row]:
    """Distinct projected rows (K1); rows holding a blank node are dropped (K11). Past ``limit``
    distinct rows, ``TooManyRows`` is raised without evaluating the rest."""
    if len(query.patterns) == 1:
        return _one_pattern_rows(index, query, limit)
    out: set[Row] = set()
    order = _variables(query.patterns)
    slots = [order.index(v) for v in query.projection]
    project = _projector(slots)
    for values in _solutions(index, query.patterns, order):
        row = project(values)
        if BNode not in map(type, row):
            out.add(row)
            if limit is not None and len(out) > limit:
                raise TooManyRows(limit)
    return out


def _projector(slots: Sequence[int]) -> Callable[[list[Node]], Row]:
    """The projected row of a solution (itemgetter: no Python call per row for several slots)."""
    if len(slots) > 1:
        return itemgetter(*slots)  # a tuple for two or more slots
    if slots:
        slot = slots[0]
        return lambda values: (values[slot],)
    return lambda values: ()


def rows_in(indexes: Iterable[JoinIndex], query: Query, limit: int | None = None) -> set[Row]:
    """Distinct rows over several indexes (models); ``TooManyRows`` past ``limit`` in all."""
    found: set[Row] = set()
    for index in indexes:
        found |= rows(index, query, limit)
        if limit is not None and len(found) > limit:
            raise TooManyRows(limit)
    return found


def _one_pattern_rows(index: JoinIndex, query: Query, limit: int | None) -> set[Row]:
    # The most frequent query (`myself sees ?x`) needs no join: scan once, project each triple.
    pattern = query.patterns[0]
    constant = [None if isinstance(t, Variable) else index.canonical(t) for t in pattern]
    positions = [[i for i, t in enumerate(pattern) if t == v] for v in query.projection]
    variables = [t for t in pattern if isinstance(t, Variable)]
    repeated = len(set(variables)) < len(variables)
    out: set[Row] = set()
    for triple in index.scan(constant[0], constant[1], constant[2]):
        if repeated and match_triple(pattern, query.projection, triple) is None:
            continue
        row = tuple(triple[where[0]] for where in positions)
        if not any(type(t) is BNode for t in row):
            out.add(row)
            if limit is not None and len(out) > limit:
                raise TooManyRows(limit)
    return out


def holds(index: JoinIndex, query: Query) -> bool:
    """True when the patterns have at least one solution."""
    order = _variables(query.patterns)
    return next(_solutions(index, query.patterns, order), None) is not None


def match_triple(
    pattern: Pattern, projection: Sequence[Variable], triple: tuple[Node, Node, Node]
) -> Row | None:
    """The projected row a single triple gives for one pattern, or None if it does not match."""
    bound: dict[Variable, Node] = {}
    for term, value in zip(pattern, triple, strict=True):
        if isinstance(term, Variable):
            if bound.setdefault(term, value) != value:
                return None
        elif term != value:
            return None
    row = tuple(bound[v] for v in projection)
    return None if any(isinstance(t, BNode) for t in row) else row


def holds_row(index: JoinIndex, pattern: Pattern, projection: Sequence[Variable], row: Row) -> bool:
    """True if some triple of the index still gives ``row`` for ``pattern``."""
    values = dict(zip(projection, row, strict=True))
    bound = tuple(values.get(t, t) if isinstance(t, Variable) else t for t in pattern)
    return holds(index, Query((bound,), (), ()))  # type: ignore[arg-type]  # terms may stay variables
