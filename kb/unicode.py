"""Text that is not valid Unicode: lone surrogates (U+D800..U+DFFF), refused wherever text enters.

Python strings may hold a lone surrogate (JSON's ``"\\ud800"``, N3's and SPARQL's ``\\ud800``
escapes produce one), but no UTF-8 document can: a literal holding one is stored fine and then
breaks every answer that names it (JSON, RDF exports, the journal). So it is refused on the way in,
with the place named, and nothing of the request is applied.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from rdflib import Literal

from kb.errors import InvalidUnicode

_SURROGATE = re.compile("[\ud800-\udfff]")


def surrogate_at(text: str) -> int | None:
    """The index of the first lone surrogate in ``text``, else None."""
    found = _SURROGATE.search(text)
    return None if found is None else found.start()


def check_text(text: str, what: str) -> None:
    """Raise ``InvalidUnicode`` naming ``what`` if ``text`` holds a lone surrogate."""
    at = surrogate_at(text)
    if at is not None:
        raise InvalidUnicode(f"{what} is not valid Unicode: it holds the lone surrogate "
                             f"U+{ord(text[at]):04X} at character {at}")


def check_terms(terms: Iterable[object], what: str) -> None:
    """``check_text`` on each RDF term (a literal's datatype included)."""
    for term in terms:
        if isinstance(term, str):
            check_text(term, what)
        if isinstance(term, Literal) and term.datatype is not None:
            check_text(term.datatype, what)
