"""Text that the KB cannot keep, refused wherever text enters.

Lone surrogates (U+D800..U+DFFF) are not valid Unicode: Python strings may hold one (JSON's
``"\\ud800"``, N3's and SPARQL's ``\\ud800`` escapes produce one), but no UTF-8 document can, so a
literal holding one is stored fine and then breaks every answer that names it (JSON, RDF exports,
the journal). The C0 controls other than tab, newline and carriage return, and U+FFFE/U+FFFF,
are valid Unicode that XML 1.0 cannot carry, not even as a character reference: a KB holding one
exports RDF/XML (and TriX) that no parser loads back. An IRI holding a space or one of
``<>"{}|^`\\`` (which Turtle's ``\\u`` escapes let in) cannot be written as Turtle or N-Triples at
all, nor loaded back from RDF/XML; one holding other white space (U+00A0, U+2028...) is not read
back from N-Triples, and a datatype IRI holding ``&`` is written unescaped into RDF/XML. Terms
holding any of these are refused on the way in, with the place named, and nothing of the request
is applied; every other character round-trips through every export format.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from rdflib import Literal, URIRef

from kb.errors import InvalidCharacter, InvalidUnicode

_SURROGATE = re.compile("[\ud800-\udfff]")
# What XML 1.0's Char production leaves out, less the surrogates (refused as invalid above).
_UNCARRIED = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]")
# What N-Triples' IRIREF production leaves out (the C0 controls are refused above), and the other
# white space (U+0085, U+00A0, U+2028...), which the grammar allows but rdflib's N-Triples reader,
# and so the KB's own, does not.
_NOT_IN_IRI = re.compile('[\x00-\x20<>"{}|^`\\\\]|\\s')
# Any character one of the three checks refuses in an IRI.
_SUSPECT_IRI = re.compile('[\x00-\x20<>"{}|^`\\\\\ud800-\udfff\ufffe\uffff]|\\s')


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


def check_iri(iri: str, what: str) -> None:
    """Raise ``InvalidCharacter`` naming ``what`` if ``iri`` holds a character no IRI may hold."""
    found = _NOT_IN_IRI.search(iri)
    if found is not None:
        raise InvalidCharacter(f"{what} is an IRI holding {found.group()!r} (U+{ord(found.group()):04X}) at "
                               f"character {found.start()}, a character no IRI may hold: Turtle and "
                               f"N-Triples could not write it; percent-encode it")


def carried(text: str) -> str:
    """``text`` without the characters ``check_carried`` refuses (for a record made of words
    someone said, where they are noise)."""
    return _UNCARRIED.sub("", text)


def carried_line(text: str) -> str:
    """``carried`` on one line: each run of white space one space (a quote of what someone said,
    kept in a record of one line)."""
    return " ".join(carried(text).split())


def check_terms(terms: Iterable[object], what: str) -> None:
    """``check_text`` and ``check_carried`` on each RDF term (a literal's datatype and language
    included), ``check_iri`` on each IRI (a datatype included)."""
    for term in terms:
        if isinstance(term, URIRef):
            if _SUSPECT_IRI.search(term) is not None:  # one search for the many IRIs of a bulk load
                check_text(term, what)
                check_carried(term, what)
                check_iri(term, what)
        elif isinstance(term, str):
            check_text(term, what)
            check_carried(term, what)
        if isinstance(term, Literal):
            for part in (term.datatype, term.language):
                if part is not None:
                    check_text(part, what)
                    check_carried(part, what)
            if term.datatype is not None:
                check_iri(term.datatype, what)
                if "&" in term.datatype:  # rdflib's RDF/XML writer puts it in an attribute unescaped
                    raise InvalidCharacter(f"{what} has a datatype IRI holding '&', which the RDF/XML export "
                                           "cannot write; name the datatype without it")
