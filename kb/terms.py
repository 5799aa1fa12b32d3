"""Statement syntax: knowledge_core's "subject predicate object" strings to rdflib terms and back.

The tokeniser is quote-aware (kb-compat §1.7): a quoted literal with spaces is one token and keeps
its language tag or datatype; names may hold parentheses, hyphens and dots; numbers may be
negative, decimal or in exponent form. Terms are always built as rdflib terms, never by pasting
strings into SPARQL or Turtle, so no pattern can inject anything.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import lru_cache
from typing import Final, TypeAlias

from rdflib import BNode, Literal, URIRef, Variable
from rdflib.namespace import RDF, XSD

from kb.errors import KbError
from kb.unicode import check_terms

ORO: Final = "http://kb.openrobots.org#"

PREFIXES: Final[Mapping[str, str]] = {
    "": ORO,
    "oro": ORO,
    "cyc": "http://sw.opencyc.org/concept/",
    "rdf": "http://www.w3.org/1999/02/22-rdf-syntax-ns#",
    "rdfs": "http://www.w3.org/2000/01/rdf-schema#",
    "owl": "http://www.w3.org/2002/07/owl#",
    "xsd": "http://www.w3.org/2001/XMLSchema#",
    "dbr": "https://dbpedia.org/resource/",
    "dbo": "https://dbpedia.org/ontology/",
    "dbp": "https://dbpedia.org/property/",
    "prov": "http://www.w3.org/ns/prov#",
    "foaf": "http://xmlns.com/foaf/0.1/",
}

Node: TypeAlias = URIRef | Literal | BNode
Term: TypeAlias = URIRef | Literal | BNode | Variable
Triple: TypeAlias = tuple[Node, Node, Node]
Pattern: TypeAlias = tuple[Term, Term, Term]
Value: TypeAlias = str | int | float | bool

# Longest namespace first so that a more specific prefix wins when shortening.
_BY_NAMESPACE: Final = sorted(
    ((ns, prefix) for prefix, ns in PREFIXES.items() if prefix not in ("", "oro")),
    key=lambda item: -len(item[0]),
)
# Names may use any letter (N3 allows non-ASCII names: pièce_1), digits and the punctuation
# knowledge_core's producers use, but may not end with a dot (N3's statement terminator).
_NAME = re.compile(r"\w(?:[\w\-.()~!$&+,;=/%]*[\w\-()~!$&+,;=/%])?")
_LOCAL = re.compile(r"(?:\w(?:[\w\-.()~!$&+,;=/%]*[\w\-()~!$&+,;=/%])?)?")
_VARIABLE = re.compile(r"\?([A-Za-z_][A-Za-z0-9_]*)")
_BRACKETED_IRI = re.compile(r"[A-Za-z][A-Za-z0-9+.\-]*:[^\s<>\"{}|\\^`]*")
_ABSOLUTE_IRI = re.compile(r"[A-Za-z][A-Za-z0-9+.\-]*://[^\s<>\"{}|\\^`]+")
_INTEGER = re.compile(r"[+-]?\d+")
_DECIMAL = re.compile(r"[+-]?\d*\.\d+")
_DOUBLE = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)[eE][+-]?\d+")
_LANG = re.compile(r"@([A-Za-z]+(?:-[A-Za-z0-9]+)*)")
_ESCAPE = re.compile(r"\\(?:u([0-9A-Fa-f]{4})|U([0-9A-Fa-f]{8})|(.))", re.DOTALL)
_SIMPLE_ESCAPES: Final = {
    "t": "\t", "n": "\n", "r": "\r", "b": "\b", "f": "\f", '"': '"', "'": "'", "\\": "\\",
}
_INTEGER_TYPES: Final = frozenset(
    XSD[name]
    for name in (
        "integer", "int", "long", "short", "byte", "nonNegativeInteger", "positiveInteger",
        "nonPositiveInteger", "negativeInteger", "unsignedLong", "unsignedInt", "unsignedShort",
        "unsignedByte",
    )
)
_FLOAT_TYPES: Final = frozenset((XSD.decimal, XSD.double, XSD.float))
#: knowledge_core's anonymous variables: those whose name starts with ``__`` (its clients write
#: every ``*`` as one); ``*`` itself becomes ``?__anon<n>``.
ANONYMOUS_MARK: Final = "__"
ANONYMOUS_PREFIX: Final = ANONYMOUS_MARK + "anon"


@dataclass(frozen=True, slots=True)
class Token:
    """One lexical unit of a statement; ``literal`` tells a quoted literal from a bare word."""

    text: str
    literal: bool


def tokenize(statement: str) -> list[Token]:
    """Split a statement into tokens, keeping quoted literals (with tag or datatype) whole."""
    tokens: list[Token] = []
    i, n = 0, len(statement)
    while i < n:
        ch = statement[i]
        if ch.isspace():
            i += 1
            continue
        if ch in "\"'":
            end = _literal_end(statement, i)
            end = _suffix_end(statement, end)
            tokens.append(Token(statement[i:end], literal=True))
            i = end
        elif ch == "<":
            close = statement.find(">", i)
            if close < 0:
                raise KbError(f"unclosed IRI '<' in {statement!r}")
            tokens.append(Token(statement[i : close + 1], literal=False))
            i = close + 1
        else:
            j = i
            while j < n and not statement[j].isspace():
                if statement[j] == '"':
                    raise KbError(f"stray quote in {statement[i:j + 1]!r} of {statement!r}")
                j += 1
            tokens.append(Token(statement[i:j], literal=False))
            i = j
    return tokens


def _literal_end(text: str, start: int) -> int:
    quote = text[start]
    triple = text.startswith(quote * 3, start)
    delim = quote * 3 if triple else quote
    i = start + len(delim)
    while i < len(text):
        ch = text[i]
        if ch == "\\":
            i += 2
            continue
        if text.startswith(delim, i):
            return i + len(delim)
        if ch == "\n" and not triple:
            break
        i += 1
    raise KbError(f"unterminated string literal in {text!r}")


def _suffix_end(text: str, end: int) -> int:
    if text.startswith("@", end) or text.startswith("^^", end):
        # A language tag never holds a dot, so "x"@en. ends the statement, as in N3.
        stops = " \t\r\n." if text[end] == "@" else " \t\r\n"
        j = end
        while j < len(text) and text[j] not in stops:
            j += 1
        return j
    return end


def unescape(body: str) -> str:
    """Resolve N3 string escapes (``\\"``, ``\\n``, ``\\uXXXX``...)."""

    def repl(m: re.Match[str]) -> str:
        if m.group(1) or m.group(2):
            return chr(int(m.group(1) or m.group(2), 16))
        esc = m.group(3)
        if esc not in _SIMPLE_ESCAPES:
            raise KbError(f"unknown escape '\\{esc}' in string literal")
        return _SIMPLE_ESCAPES[esc]

    return _ESCAPE.sub(repl, body)


def parse_literal(token: str) -> Literal:
    quote = token[0]
    end = _literal_end(token, 0)
    delim = quote * 3 if token.startswith(quote * 3) and end - len(quote * 3) >= 3 else quote
    body = unescape(token[len(delim) : end - len(delim)])
    suffix = token[end:]
    if not suffix:
        return Literal(body)
    if lang := _LANG.fullmatch(suffix):
        return Literal(body, lang=lang.group(1))
    if suffix.startswith("^^"):
        target = suffix[2:]
        if target.startswith(("\"", "'")):
            raise KbError(f"the datatype of {token} must be an IRI, not a literal")
        datatype = parse_name(target, f"datatype of {token}")
        return Literal(body, datatype=datatype)
    raise KbError(f"unexpected text {suffix!r} after literal {token[:end]}")


def parse_name(word: str, where: str) -> URIRef:
    """A bare word, CURIE, <IRI> or absolute IRI to an IRI."""
    if word.startswith("<"):
        iri = word[1:-1]
        if not word.endswith(">") or not _BRACKETED_IRI.fullmatch(iri):
            raise KbError(f"{where}: {word} is not an absolute IRI")
        return URIRef(iri)
    if _ABSOLUTE_IRI.fullmatch(word):
        return URIRef(word)
    if word.startswith("_:"):
        raise KbError(f"{where}: blank nodes are not supported ({word!r})")
    if ":" in word:
        prefix, _, local = word.partition(":")
        if prefix not in PREFIXES:
            raise KbError(f"{where}: unknown prefix '{prefix}:' in {word!r}")
        if not _LOCAL.fullmatch(local):
            raise KbError(f"{where}: invalid local name {local!r} in {word!r}")
        return URIRef(PREFIXES[prefix] + local)
    if not _NAME.fullmatch(word):
        raise KbError(f"{where}: invalid name {word!r}")
    return URIRef(ORO + word)


class TermParser:
    """Turns tokens into terms; numbers the anonymous ``*`` variables of one statement list."""

    def __init__(self) -> None:
        self._anonymous = 0

    def term(self, token: Token, position: str, statement: str) -> Term:
        term = self._term(token, position, statement)
        check_terms((term,), f"the {position} of {statement!r}")
        return term

    def _term(self, token: Token, position: str, statement: str) -> Term:
        where = f"{position} of {statement!r}"
        if token.literal:
            try:
                return parse_literal(token.text)
            except KbError as exc:
                raise KbError(f"{where}: {exc}") from None
        word = token.text
        if word == "*":
            self._anonymous += 1
            return Variable(f"{ANONYMOUS_PREFIX}{self._anonymous}")
        if word.startswith("?"):
            if not _VARIABLE.fullmatch(word):
                raise KbError(f"{where}: invalid variable {word!r}")
            return Variable(word[1:])
        if word == "a" and position == "predicate":
            return RDF.type
        if word in ("true", "false"):
            return Literal(word == "true")
        if _INTEGER.fullmatch(word):
            return Literal(word, datatype=XSD.integer)
        if _DECIMAL.fullmatch(word):
            return Literal(word, datatype=XSD.decimal)
        if _DOUBLE.fullmatch(word):
            return Literal(word, datatype=XSD.double)
        return parse_name(word, where)


def parse_statement(statement: str, parser: TermParser | None = None) -> Pattern:
    """Parse one statement or pattern; variables are allowed here, callers forbid them where needed."""
    if not isinstance(statement, str):
        raise KbError(f"a statement must be a string, got {type(statement).__name__}: {statement!r}")
    plain = _plain_statement(statement)
    if plain is not None:
        return plain
    tokens = tokenize(statement)
    # N3 ends a statement with a dot: accept "s p o ." and "s p o." as knowledge_core's parser does.
    last = tokens[-1] if tokens else None
    if len(tokens) == 4 and last == Token(".", False):
        tokens = tokens[:3]
    elif len(tokens) == 3 and last and not last.literal and len(last.text) > 1 and last.text.endswith("."):
        tokens[2] = Token(last.text[:-1], False)
    if len(tokens) != 3:
        raise KbError(
            f"invalid statement {statement!r}: expected 3 terms (subject predicate object), got {len(tokens)}"
        )
    parser = parser or TermParser()
    s = parser.term(tokens[0], "subject", statement)
    p = parser.term(tokens[1], "predicate", statement)
    o = parser.term(tokens[2], "object", statement)
    if isinstance(s, Literal):
        raise KbError(f"invalid statement {statement!r}: the subject may not be a literal")
    if isinstance(p, Literal):
        raise KbError(f"invalid statement {statement!r}: the predicate may not be a literal")
    return (s, p, o)


def _plain_statement(statement: str) -> Triple | None:
    """The common statement of three bare words (no quote, no IRI in brackets, no variable), each
    word's term cached; None for anything else, which the general path parses (and refuses with
    its message). Bulk loads are mostly such statements, and cached terms are the KB's own
    interned objects, so the index compares them by identity. A pattern with a variable is left
    to the general path before any word is cached: queries are compiled once each
    (``kb.arguments``), and the words of one-off ones (the record of each perceived fact, asked
    about on every tick) would fill the cache with terms used once."""
    if '"' in statement or "'" in statement or "<" in statement or "?" in statement or "*" in statement:
        return None
    words = statement.split()
    if len(words) == 4 and words[3] == ".":
        del words[3]
    elif len(words) == 3 and len(words[2]) > 1 and words[2].endswith("."):
        words[2] = words[2][:-1]
    if len(words) != 3:
        return None
    s, p, o = _word(words[0], False), _word(words[1], True), _word(words[2], False)
    if type(s) is not URIRef or type(p) is not URIRef or o is None:
        return None
    return (s, p, o)


@lru_cache(maxsize=32768)
def _word(word: str, predicate: bool) -> URIRef | Literal | None:
    """A bare word's ground term (None: a variable, or not a valid term)."""
    if word == "*" or word.startswith("?"):
        return None
    try:
        term = TermParser().term(Token(word, False), "predicate" if predicate else "object", word)
    except KbError:
        return None
    return term if isinstance(term, URIRef | Literal) else None


def as_list(statements: str | Iterable[str]) -> list[str]:
    if isinstance(statements, str):
        return [statements]
    if not isinstance(statements, Iterable):
        raise KbError(f"expected a statement string or a list of them, got {statements!r}")
    items = list(statements)
    for item in items:
        if not isinstance(item, str):
            raise KbError(f"statements must be strings, got {type(item).__name__}: {item!r}")
    return items


def parse_patterns(patterns: str | Iterable[str]) -> list[Pattern]:
    """Parse a conjunction of patterns, numbering ``*`` across the whole list."""
    parser = TermParser()
    return [parse_statement(p, parser) for p in as_list(patterns)]


@lru_cache(maxsize=4096)
def parse_ground(statement: str) -> Triple:
    """Parse a statement that must not contain variables (add, update, ground retract)."""
    s, p, o = parse_statement(statement)
    for term in (s, p, o):
        if isinstance(term, Variable):
            shown = "*" if term.startswith(ANONYMOUS_PREFIX) else f"?{term}"
            raise KbError(f"invalid statement {statement!r}: variable {shown} not allowed when adding facts")
    return (s, p, o)  # type: ignore[return-value]  # variables excluded just above


def is_anonymous(var: Variable) -> bool:
    return var.startswith(ANONYMOUS_MARK)


@lru_cache(maxsize=131072)
def shorten_iri(iri: str) -> str:
    """ORO terms without prefix, other known namespaces as CURIEs, anything else in full (K17).
    Cached: answers and views of the KB name the same terms again and again."""
    return _short_form(iri)


def _short_form(iri: str) -> str:
    if iri.startswith(ORO):
        local = iri[len(ORO) :]
        # "true", "false" and numbers would read back as literals; "a" reads back as the same name
        # everywhere but in predicate position, where a client writes rdf:type anyway.
        if _NAME.fullmatch(local) and local not in ("true", "false") and not _is_number(local):
            return local
        if _LOCAL.fullmatch(local):
            return "oro:" + local
        return iri
    for ns, prefix in _BY_NAMESPACE:
        if iri.startswith(ns):
            local = iri[len(ns) :]
            if _LOCAL.fullmatch(local):
                return f"{prefix}:{local}"
            break
    return iri


def _is_number(word: str) -> bool:
    return bool(_INTEGER.fullmatch(word) or _DECIMAL.fullmatch(word) or _DOUBLE.fullmatch(word))


def to_python(lit: Literal) -> Value:
    """A literal as a native JSON value: int, float, bool or string."""
    dt = lit.datatype
    if dt is not None:
        try:
            if dt in _INTEGER_TYPES:
                return int(lit)
            if dt in _FLOAT_TYPES:
                return float(lit)
        except ValueError:
            return str(lit)
        if dt == XSD.boolean:
            return str(lit).strip().lower() in ("true", "1")
    return str(lit)


def shorten(term: Node) -> Value | None:
    """The output form of a term; ``None`` for blank nodes, which never appear in results."""
    if type(term) is URIRef:  # the common case, without rdflib's slower isinstance checks
        return shorten_iri(str(term))
    if isinstance(term, URIRef):
        return shorten_iri(str(term))
    if isinstance(term, Literal):
        return to_python(term)
    return None


def format_term(term: Node) -> str:
    """A term written back in statement syntax, so it can be reused in a later statement."""
    if isinstance(term, URIRef):
        # Not through shorten_iri's cache: a term written back is often one used once (the
        # record of a perceived fact, checked on every tick), and a process-wide cache filled
        # with those grew the service by megabytes an hour, long after its vocabulary was in.
        short = _short_form(str(term))
        return f"<{short}>" if short == str(term) else short
    if isinstance(term, Literal):
        body = str(term).replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
        if term.language:
            return f'"{body}"@{term.language}'
        if term.datatype is not None and term.datatype != XSD.string:
            return f'"{body}"^^{format_term(term.datatype)}'
        return f'"{body}"'
    raise KbError("blank nodes cannot be written as statements")


def format_triple(triple: Triple) -> str:
    return " ".join(format_term(t) for t in triple)
