"""A time budget, a row cap and string bounds applied to a translated rdflib query before it runs.

The deadline is checked where rdflib's engine spends its time:
- every triple it reads (kb.deadline.TimedIndex, under the store);
- every solution of a join, an OPTIONAL, a MINUS, a UNION and a VALUES block: these multiply
  solutions without reading the store (``VALUES ?a {1 2 3 4 5 6 7 8 9 10}`` nine times is a
  billion rows from 250 characters), so each gets a filter that only looks at the clock;
- every expression evaluated (a chain of BINDs reads nothing either);
- REGEX and REPLACE, which get the rest of the budget as their match timeout (kb.sparqlregex).
Every expression's Python errors are SPARQL expression errors and its numbers are bounded
(kb.sparqlexpr), so no value makes a server error or a conversion that holds the GIL for minutes.
Every string an expression builds is measured (kb.sparqlspend: CONCAT before it joins, REPLACE
as it goes, the others on their result; GROUP_CONCAT's values as they are gathered), so no
expression builds more than the bounds allow, with or without a deadline.
The row cap is a LIMIT of one row more than allowed on the solutions of a SELECT, so rows are
never produced past it and one too many tells that the answer would have been larger.
"""

from __future__ import annotations

from collections.abc import Callable
from types import MethodType
from typing import Any

from rdflib import Literal
from rdflib.plugins.sparql.algebra import traverse
from rdflib.plugins.sparql.operators import string
from rdflib.plugins.sparql.parserutils import CompValue, Expr, value
from rdflib.query import Result

from kb.deadline import Deadline
from kb.errors import TooManyRows
from kb.sparqlexpr import guarded
from kb.sparqlregex import bound_regex
from kb.sparqlspend import Spend

# The algebra nodes that make solutions without reading the store.
_MULTIPLYING = frozenset({"Join", "LeftJoin", "Minus", "Union", "ToMultiSet"})


def bound(prepared: Any, deadline: Deadline | None, max_rows: int | None, spend: Spend | None = None) -> None:
    """Make ``prepared`` (rdflib's translated query, not shared) stop at the deadline, build no
    string past ``spend``'s bounds and produce at most ``max_rows + 1`` SELECT rows."""
    algebra = prepared.algebra
    spend = spend if spend is not None else Spend()
    clock = Expr("deadline", _on_time(deadline)) if deadline is not None else None
    seen: set[int] = set()

    def visit(node: Any) -> CompValue | None:
        if id(node) in seen:
            return None
        seen.add(id(node))
        if isinstance(node, Expr) and node._evalfn is not None:
            _bound_expression(node, deadline, spend)
        elif isinstance(node, CompValue) and node.name == "Aggregate_GroupConcat":
            node["vars"] = _gathered(node.vars, node.separator, spend)
        if clock is not None and isinstance(node, CompValue) and node.name in _MULTIPLYING:
            # LeftJoin reads the _vars of its first operand: the filter carries them on.
            return CompValue("Filter", p=node, expr=clock, no_isolated_scope=True, _vars=node._vars)
        return None

    traverse(algebra, visitPost=visit)
    if max_rows is not None and algebra.name == "SelectQuery":
        algebra["p"] = CompValue("Slice", p=algebra.p, start=0, length=max_rows + 1)


def _bound_expression(node: Expr, deadline: Deadline | None, spend: Spend) -> None:
    name = node.name.removeprefix("Builtin_")
    if node.name == "Builtin_CONCAT":
        node._evalfn = MethodType(_concat(spend), node)
    elif not bound_regex(node, deadline, spend):
        original: Callable[[Any], Any] = node._evalfn  # type: ignore[assignment]

        def evaluate(expr: Expr, ctx: Any) -> Any:
            result = original(ctx)
            if isinstance(result, str):
                spend.string(len(result), name)
            return result

        node._evalfn = MethodType(evaluate, node)
    built: Callable[[Any], Any] = node._evalfn  # type: ignore[assignment]
    node._evalfn = MethodType(guarded(node, built, name), node)
    if deadline is not None:
        measured: Callable[[Any], Any] = node._evalfn

        def timed(expr: Expr, ctx: Any) -> Any:
            deadline.check()
            return measured(ctx)

        node._evalfn = MethodType(timed, node)


def _concat(spend: Spend) -> Callable[[Expr, Any], Literal]:
    """rdflib's CONCAT (dt and lang kept only when all arguments agree), its arguments evaluated
    once and measured before they are joined."""

    def evaluate(expr: Expr, ctx: Any) -> Literal:
        args = expr.arg
        texts = [string(arg) for arg in args]
        spend.string(sum(len(t) for t in texts), "CONCAT")
        datatypes = {t.datatype for t in texts}
        languages = {t.language for t in texts}
        return Literal("".join(texts), datatype=datatypes.pop() if len(datatypes) == 1 else None,
                       lang=languages.pop() if len(languages) == 1 else None)

    return evaluate


def _gathered(expression: Any, separator: Any, spend: Spend) -> Expr:
    """GROUP_CONCAT's expression, each value it gathers measured (their join is their sum)."""
    gap = len(separator) if isinstance(separator, str) else 1

    def evaluate(expr: Expr, ctx: Any) -> Any:
        found = value(ctx, expression)  # unbound: NotBoundError, which GROUP_CONCAT skips
        if isinstance(found, str):
            spend.kept(len(found) + gap, "GROUP_CONCAT")
        return found

    return Expr("gathered", evaluate)


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
