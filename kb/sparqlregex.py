"""SPARQL's REGEX and REPLACE under a query's deadline and string bounds.

rdflib evaluates them with Python's ``re``, whose backtracking is exponential on patterns such
as ``(a|aa)+$`` and cannot be interrupted: one FILTER holds the GIL and the KB lock for minutes.
Refusing "dangerous" patterns cannot be done reliably (nested quantifiers are only one way to
backtrack exponentially; overlapping alternatives and backreferences are others), and bounding
the text does not help (40 characters suffice). So the functions are evaluated here with the
``regex`` package instead: the same syntax as ``re``, a ``timeout`` that stops a match in the
middle, and the GIL released while it matches. The timeout is what is left of the query's
budget, so a regex cannot outlive the query. A REPLACE counts what it builds as it goes
(``kb.sparqlspend``): ``REPLACE(?s, "", ?long)`` puts ``?long`` between every two characters.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import reduce
from operator import or_
from types import MethodType
from typing import Any

import regex
from rdflib import Literal
from rdflib.plugins.sparql.operators import string
from rdflib.plugins.sparql.parserutils import Expr

from kb.deadline import Deadline
from kb.errors import InvalidRegex, QueryTimeout
from kb.sparqlspend import Spend

# The XPath flags SPARQL defines that rdflib maps (others are ignored, as rdflib does).
_FLAGS = {"i": regex.IGNORECASE, "s": regex.DOTALL, "m": regex.MULTILINE}
# SPARQL writes group references in a replacement as $1; Python as \1.
_GROUP_REF = regex.compile(r"\$([0-9]*)")


def _group(ref: Any) -> str:
    """``$N`` as a group reference (``\\g<N>``: ``\\0`` would be a NUL character)."""
    return f"\\g<{ref.group(1)}>" if ref.group(1) else "$"


def _flags(flags: Any) -> int:
    return reduce(or_, (_FLAGS.get(f, 0) for f in str(flags)), 0) if flags else 0


def _run(deadline: Deadline | None, pattern: str, call: Callable[..., Any], *args: Any) -> Any:
    try:
        return call(*args, timeout=None if deadline is None else deadline.remaining(), concurrent=True)
    except TimeoutError:
        raise QueryTimeout(deadline.seconds if deadline is not None else 0.0) from None
    except regex.error as exc:
        raise InvalidRegex(f"invalid regular expression {pattern!r} in the query: {exc}") from None


def _regex(deadline: Deadline | None, spend: Spend) -> Callable[[Expr, Any], Literal]:
    def evaluate(expr: Expr, ctx: Any) -> Literal:
        text, pattern = string(expr.text), str(string(expr.pattern))
        found = _run(deadline, pattern, regex.search, pattern, str(text), _flags(expr.flags))
        return Literal(found is not None)

    return evaluate


def _replace(deadline: Deadline | None, spend: Spend) -> Callable[[Expr, Any], Literal]:
    def evaluate(expr: Expr, ctx: Any) -> Literal:
        text, pattern = string(expr.arg), str(string(expr.pattern))
        template = _GROUP_REF.sub(_group, str(string(expr.replacement)))
        built = len(text)  # at most: what is not replaced, plus every replacement

        def replacement(match: Any) -> str:
            nonlocal built
            piece: str = match.expand(template)
            built += len(piece)
            if built > spend.max_string:
                spend.string(built, "REPLACE")
            return piece

        replaced = _run(deadline, pattern, regex.sub, pattern, replacement, str(text), 0, _flags(expr.flags))
        return Literal(replaced, datatype=text.datatype, lang=text.language)

    return evaluate


_EVALUATORS = {"Builtin_REGEX": _regex, "Builtin_REPLACE": _replace}


def bound_regex(node: Any, deadline: Deadline | None, spend: Spend) -> bool:
    """Make a REGEX or REPLACE expression node of a parsed query evaluate under ``deadline``
    and ``spend`` (rdflib binds each expression node to its function when it parses the query);
    True if the node was one."""
    make = _EVALUATORS.get(getattr(node, "name", ""))
    if make is not None and isinstance(node, Expr):
        node._evalfn = MethodType(make(deadline, spend), node)
        return True
    return False
