"""A SPARQL expression that fails is an error value, never a server error; its numbers are bounded.

SPARQL defines what an expression error does: the expression is unbound (a BIND, a projected
expression), a FILTER is false. rdflib raises its ``SPARQLError`` for the errors it foresees, but
its operators call Python on the values themselves, and Python raises its own errors for values
that are valid RDF: decimal ``Overflow``/``InvalidOperation`` (``"1E999999"^^xsd:decimal * 10``),
``OverflowError``/``ValueError`` for an infinite or NaN double turned into an integer (CEIL,
ROUND, SUBSTR's positions), ``IndexError`` for a REPLACE template naming a group the pattern does
not have, ``TypeError`` for a naive dateTime minus an aware one or a duration added to a date,
``AttributeError`` for a function of an ill-typed literal (rdflib keeps no value for
``"2024-13-45T99:99:99"^^xsd:dateTime``), ``binascii.Error`` (a ``ValueError``) for hexBinary.
Each expression is evaluated here with those errors turned into ``SPARQLError``, as rdflib does
for its own.

Time is the other half. A decimal holds ``1E999999`` in a few bytes, but CEIL, FLOOR and a cast to
xsd:integer turn it into a Python integer of a million digits, which holds the GIL for more than a
minute (no deadline can interrupt it). So a number an expression takes (a constant, a variable's
value) or makes is an error value when its magnitude reaches ``10**MAX_DIGITS``: every step then
works on numbers of a bounded size. Python already refuses to write a longer integer as text.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from decimal import Decimal
from typing import Any

from rdflib import Literal, Variable
from rdflib.plugins.sparql.parserutils import Expr
from rdflib.plugins.sparql.sparql import SPARQLError

#: Decimal digits of the largest magnitude an expression may take or make (Python writes no
#: longer integer as text: ``sys.get_int_max_str_digits``).
MAX_DIGITS = 4300
_MAX_BITS = int(MAX_DIGITS * 3.33) + 1

#: What Python raises when an rdflib operator meets a value it cannot compute with: the
#: evaluation's error, not the service's. (The KB's own errors, KbError, are none of these.)
EXPRESSION_ERRORS: tuple[type[Exception], ...] = (
    ArithmeticError, ValueError, TypeError, AttributeError, IndexError)
#: What may come out of a query's evaluation as a whole: the above, or rdflib's own errors where it
#: has no error value to give (an aggregate).
EVALUATION_ERRORS: tuple[type[Exception], ...] = (SPARQLError, *EXPRESSION_ERRORS)


def too_large(term: Any) -> bool:
    """Whether ``term`` is a numeric literal whose magnitude reaches ``10**MAX_DIGITS``."""
    if not isinstance(term, Literal):
        return False
    number = term.value
    if isinstance(number, Decimal):
        return number.is_finite() and number != 0 and number.adjusted() >= MAX_DIGITS
    return isinstance(number, int) and number.bit_length() > _MAX_BITS


def _check(term: Any, what: str) -> None:
    if too_large(term):
        raise SPARQLError(f"{what}: a number of more than {MAX_DIGITS} digits")


def _inputs(expr: Expr, ctx: Any) -> Iterable[Any]:
    """The constants and variable values an expression reads itself (sub-expressions check
    their own results). The raw children are read through dict: CompValue's own accessors
    would evaluate them."""
    for child in dict.values(expr):
        for item in child if isinstance(child, list) else (child,):
            if isinstance(item, Literal):
                yield item
            elif isinstance(item, Variable) and hasattr(ctx, "get"):
                yield ctx.get(item)


def guarded(expr: Expr, evaluate: Callable[[Any], Any], name: str) -> Callable[[Expr, Any], Any]:
    """``evaluate`` (an expression node's function of the context) whose inputs and result are
    held to ``MAX_DIGITS`` and whose Python errors are SPARQL expression errors."""

    def run(node: Expr, ctx: Any) -> Any:
        for term in _inputs(expr, ctx):
            _check(term, f"{name} cannot take its argument")
        try:
            result = evaluate(ctx)
        except EXPRESSION_ERRORS as exc:
            raise SPARQLError(f"{name}: {type(exc).__name__}: {exc}") from None
        _check(result, f"{name} cannot make its result")
        return result

    return run
