"""Text that the KB cannot keep, refused wherever text enters.

Lone surrogates (U+D800..U+DFFF) are not valid Unicode: Python strings may hold one (JSON's
``"\\ud800"``, N3's and SPARQL's ``\\ud800`` escapes produce one), but no UTF-8 document can, so a
literal holding one is stored fine and then breaks every answer that names it (JSON, RDF exports,
the journal). The C0 controls other than tab, newline and carriage return, and U+FFFE/U+FFFF,
are valid Unicode that XML 1.0 cannot carry, not even as a character reference: a KB holding one
exports RDF/XML (and TriX) that no parser loads back. Terms holding either are refused on the way
in, with the place named, and nothing of the request is applied; every other character
round-trips through every export format.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from rdflib import Literal

from kb.errors import InvalidCharacter, InvalidUnicode

_SURROGATE = re.compile("[\ud800-\udfff]")
# What XML 1.0's Char production leaves out, less the surrogates (refused as invalid above).
_UNCARRIED = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]")


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


def check_carried(text: str, what: str) -> None:
    """Raise ``InvalidCharacter`` naming ``what`` if ``text`` holds a character that RDF/XML
    cannot carry."""
    found = _UNCARRIED.search(text)
    if found is not None:
        raise InvalidCharacter(f"{what} holds U+{ord(found.group()):04X} at character "
                               f"{found.start()}, a character that RDF/XML (XML 1.0) cannot carry: the KB "
                               f"could not be exported and loaded back; remove it")


def carried(text: str) -> str:
    """``text`` without the characters ``check_carried`` refuses (for a record made of words
    someone said, where they are noise)."""
    return _UNCARRIED.sub("", text)


def check_terms(terms: Iterable[object], what: str) -> None:
    """``check_text`` and ``check_carried`` on each RDF term (a literal's datatype and language
    included)."""
    for term in terms:
        if isinstance(term, str):
            check_text(term, what)
            check_carried(term, what)
        if isinstance(term, Literal):
            for part in (term.datatype, term.language):
                if part is not None:
                    check_text(part, what)
                    check_carried(part, what)
