"""Arguments of the KB's methods: parsing and validation, so that bad input is a KbError.

Every public method of ``KB`` accepts what knowledge_core's clients pass (a string or a list of
statements, ``models`` as a list, ``vars`` with or without ``?``) and refuses anything else with a
message that says what is wrong, before anything is written.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping, Sequence
from functools import lru_cache
from typing import Any, TypedDict

from rdflib import Variable

from kb.errors import KbError
from kb.models import ALL_MODELS, Model
from kb.query import Query, Row, build_query, solve
from kb.terms import Node, Pattern, TermParser, Triple, as_list, parse_patterns, shorten
from kb.terms import tokenize as _tokenize

MODEL_NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.\-]*")
Models_ = Sequence[str] | str | None


class Changes(TypedDict, total=False):
    """One model's part of ``apply_models``: statements to assert and to retract in it."""

    add: Sequence[str]
    remove: Sequence[str]


def compiled(patterns: tuple[str, ...], vars: Sequence[str] | str | None) -> Query:
    names: tuple[str, ...] | None
    if vars is None or isinstance(vars, str):
        names = (vars,) if vars else None
    elif isinstance(vars, Sequence):
        names = tuple(vars) or None
    else:
        raise KbError(f"vars must be a list of variable names, got {vars!r}")
    return compiled_query(patterns, names)


@lru_cache(maxsize=2048)
def compiled_query(patterns: tuple[str, ...], vars: tuple[str, ...] | None) -> Query:
    return build_query(parse_patterns(patterns), list(vars) if vars else None)


def render(query: Query, found: Iterable[Row], shorts: dict[Node, Any] | None = None) -> list[dict[str, Any]]:
    """Rows as dicts of output values, in a deterministic order (sorted by their text).

    ``shorts`` caches each term's output form across calls (the KB's interner keeps one). When
    every value is a string (names, labels), the rows sort as they are: the same order as by
    their text, without a key per row."""
    known: dict[Node, Any] = {} if shorts is None else shorts
    rows = list(found)
    terms = {t for row in rows for t in row}
    for term in terms:
        # Not `terms - known.keys()`: a set minus a dict view iterates the whole view, and the KB's
        # cache holds every term ever rendered: O(KB size) per query.
        if term not in known:
            known[term] = shorten(term)
    value = known.__getitem__
    values = [tuple(map(value, row)) for row in rows]
    if all(type(value(t)) is str for t in terms):
        values.sort()
    else:
        values.sort(key=lambda row: tuple(str(v) for v in row))
    names = query.names
    if len(names) == 1:
        name = names[0]
        return [{name: v} for (v,) in values]
    return [dict(zip(names, row, strict=True)) for row in values]


def matches(model: Model, patterns: Sequence[Pattern]) -> list[Triple]:
    found: set[Triple] = set()
    for binding in solve(model.closure, patterns):
        for s, p, o in patterns:
            found.add(tuple(binding.get(t, t) if isinstance(t, Variable) else t for t in (s, p, o)))  # type: ignore[arg-type]
    return [t for t in found if t in model.asserted]


def model_names(models: Models_) -> list[str]:
    if models is None:
        return []
    names = [models] if isinstance(models, str) else list(models)
    for name in names:
        if not isinstance(name, str) or not MODEL_NAME.fullmatch(name):
            raise KbError(f"invalid model name {name!r}")
    return names


def model_changes(changes: Any) -> dict[str, tuple[list[str], list[str]]]:
    """``apply_models``' argument as (add, remove) statement lists per model name: a mapping of
    model names (each model named, not ``all``) to ``{"add": [...], "remove": [...]}``."""
    if not isinstance(changes, Mapping) or not changes:
        raise KbError(f"apply_models takes a mapping of model names to their changes "
                      f"({{'person_bob': {{'add': [...], 'remove': [...]}}}}), got {changes!r}")
    out: dict[str, tuple[list[str], list[str]]] = {}
    for name, change in changes.items():
        model_names([name])
        if name == ALL_MODELS:
            raise KbError("apply_models names each model it changes; 'all' is not one")
        if not isinstance(change, Mapping) or set(change) - {"add", "remove"}:
            raise KbError(f"the changes of model {name!r} must be {{'add': [...], 'remove': [...]}}, "
                          f"got {change!r}")
        out[name] = (as_list(change.get("add", ())), as_list(change.get("remove", ())))
    return out


def lifespan_seconds(value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value < 0:
        raise KbError(f"lifespan must be a number of seconds >= 0, got {value!r}")
    return float(value)


def is_statement(text: str) -> bool:
    try:
        return len(_tokenize(text)) == 3
    except KbError:
        return False


def parse_term(text: str) -> Node:
    node = optional_term(text)
    if node is None:
        raise KbError(f"{text!r} is not a term")
    return node


def optional_term(text: str) -> Node | None:
    if not isinstance(text, str) or not text.strip():
        raise KbError(f"expected a term, got {text!r}")
    return _cached_term(text)


@lru_cache(maxsize=8192)
def _cached_term(text: str) -> Node | None:
    # Dialogue grounding asks about the same few hundred terms on every KB change.
    try:
        tokens = _tokenize(text.strip())
    except KbError:
        return None
    if len(tokens) != 1:
        return None
    try:
        node = TermParser().term(tokens[0], "term", text)
    except KbError:
        return None
    return None if isinstance(node, Variable) else node
