"""A time budget and a row cap applied to a translated rdflib query before it runs.

The deadline is checked where rdflib's engine spends its time:
- every triple it reads (kb.deadline.TimedIndex, under the store);
- every solution of a join, an OPTIONAL, a MINUS, a UNION and a VALUES block: these multiply
  solutions without reading the store (``VALUES ?a {1 2 3 4 5 6 7 8 9 10}`` nine times is a
  billion rows from 250 characters), so each gets a filter that only looks at the clock;
- REGEX and REPLACE, which get the rest of the budget as their match timeout (kb.sparqlregex).
The row cap is a LIMIT of one row more than allowed on the solutions of a SELECT, so rows are
never produced past it and one too many tells that the answer would have been larger.
"""

from __future__ import annotations

from typing import Any

from rdflib import Literal
from rdflib.plugins.sparql.algebra import traverse
from rdflib.plugins.sparql.parserutils import CompValue, Expr
from rdflib.query import Result

from kb.deadline import Deadline
from kb.errors import TooManyRows
from kb.sparqlregex import bound_regex

# The algebra nodes that make solutions without reading the store.
_MULTIPLYING = frozenset({"Join", "LeftJoin", "Minus", "Union", "ToMultiSet"})


def bound(prepared: Any, deadline: Deadline | None, max_rows: int | None) -> None:
    """Make ``prepared`` (rdflib's translated query, not shared) stop at the deadline and produce
    at most ``max_rows + 1`` SELECT rows."""
    algebra = prepared.algebra
    if deadline is not None:
        clock = Expr("deadline", _on_time(deadline))

        def visit(node: Any) -> CompValue | None:
            bound_regex(node, deadline)
            if isinstance(node, CompValue) and node.name in _MULTIPLYING:
                # LeftJoin reads the _vars of its first operand: the filter carries them on.
                return CompValue("Filter", p=node, expr=clock, no_isolated_scope=True, _vars=node._vars)
            return None

        traverse(algebra, visitPost=visit)
    if max_rows is not None and algebra.name == "SelectQuery":
        algebra["p"] = CompValue("Slice", p=algebra.p, start=0, length=max_rows + 1)


def _on_time(deadline: Deadline) -> Any:
    true = Literal(True)

    def evaluate(expr: Expr, ctx: Any) -> Literal:
        deadline.check()
        return true

    return evaluate


def check_size(result: Result, max_rows: int | None) -> None:
    """``TooManyRows`` when a SELECT has more rows, or a CONSTRUCT or DESCRIBE graph more
    triples, than ``max_rows``. The SELECT rows are read here (the caller holds the KB lock)."""
    if max_rows is None:
        return
    if result.type == "SELECT":
        size = len(result.bindings)
    elif result.type in ("CONSTRUCT", "DESCRIBE") and result.graph is not None:
        size = len(result.graph)
    else:
        return
    if size > max_rows:
        raise TooManyRows(max_rows)
