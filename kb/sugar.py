"""knowledge_core's conveniences, defined once on top of the primitive calls.

``kb[...]``, ``in``, ``+=``, ``-=``, ``revise`` and the housekeeping calls (kb-compat §3) mean the
same whatever answers ``find``/``exist``/``lookup`` and carries out ``update``/``remove``: the
in-process ``KB`` and the store replica ``RemoteKB`` both inherit them from ``KnowledgeCoreSugar``.
"""

from __future__ import annotations

import inspect
from collections.abc import Sequence
from typing import Any, Protocol, TypeVar

from kb.arguments import Models_, is_statement
from kb.errors import KbError
from kb.terms import as_list

__version__ = "0.1.0"
_ADD_METHODS = frozenset({"add", "safe_add", "update", "safe_update", "revision"})
_RETRACT_METHODS = frozenset({"retract", "remove", "delete"})
_LISTED_METHODS = ("about", "add", "classesof", "clear", "details", "exist", "find", "hello", "label",
                   "load", "lookup", "remove", "revise", "save", "sparql", "stats", "subscribe", "update")


class Primitives(Protocol):
    """The calls the conveniences are made of."""

    def find(self, patterns: str | Sequence[str], vars: Sequence[str] | None = None,
             models: Models_ = None, *, max_rows: int | None = None) -> list[Any]: ...

    def exist(self, patterns: str | Sequence[str], models: Models_ = None) -> bool: ...

    def lookup(self, query: str, models: Models_ = None) -> list[list[str]]: ...

    def update(self, stmts: str | Sequence[str], models: Models_ = None, lifespan: float = 0) -> None: ...

    def remove(self, stmts: str | Sequence[str], models: Models_ = None) -> int: ...


Self = TypeVar("Self", bound=Primitives)


class KnowledgeCoreSugar:
    """Mixin: the calls of kb-compat §3 that are shorthand for others."""

    def __getitem__(self: Primitives, key: str | Sequence[Any]) -> list[Any]:
        models: Models_ = None
        if isinstance(key, tuple):
            if key and isinstance(key[-1], list) and len(key) > 1:
                key, models = key[:-1], key[-1]
            parts: list[str] = []
            for part in key:
                parts.extend(as_list(part))
            return self.find(parts, models=models)
        if isinstance(key, str) and not is_statement(key):
            return self.lookup(key)
        return self.find(key)

    def __contains__(self: Primitives, item: object) -> bool:
        if not isinstance(item, str):
            return False
        if is_statement(item):
            return self.exist(item)
        return bool(self.lookup(item))

    def revise(self: Primitives, stmts: str | Sequence[str], policy: dict[str, Any]) -> int | None:
        """``policy``: ``{"method": add|update|retract|..., "models": [...], "lifespan": s}``.
        A retraction returns the number of asserted triples it removed; an addition None."""
        if not isinstance(policy, dict) or "method" not in policy:
            raise KbError("revise needs a policy with a 'method'")
        method = str(policy["method"]).lower()
        if method in _ADD_METHODS:
            self.update(stmts, policy.get("models"), policy.get("lifespan", 0) or 0)
            return None
        if method in _RETRACT_METHODS:
            return self.remove(stmts, policy.get("models"))
        raise KbError(f"unknown revise method {policy['method']!r}; use add, update or retract")

    def __iadd__(self: Self, stmts: str | Sequence[str]) -> Self:
        self.update(stmts)
        return self

    def __isub__(self: Self, stmts: str | Sequence[str]) -> Self:
        self.remove(stmts)
        return self

    def hello(self) -> str:
        return f"situated {__version__}"

    def stats(self) -> dict[str, Any]:
        return {"name": "situated", "version": __version__, "reasoning_enabled": True}

    def methods(self) -> list[str]:
        return [f"{n}{inspect.signature(getattr(self, n))}" for n in _LISTED_METHODS]
