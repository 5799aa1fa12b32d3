"""What English is still written in the Python of dialogue/ rather than in its language folders
(issue 28): found by reading the code's syntax trees, so that a test can hold it to a list that only
shrinks and the issue's figures can be recounted on any commit (`python -m tests.englishcode [ROOT]`).

- a *word table*: a literal collection (set, frozenset, tuple, list, dict; at module level or in a
  function, a `x in ("a", "b")` included) of two or more lower-case words, where not every word is
  one of the code's own names (the values of a `Literal[...]` of the module or of a name it imports
  from another module of the project — an alias, or a class whose fields are typed so —, the kinds,
  roles and keys the code passes around rather than hears);
- a *spatial-preposition table*: a word table with two or more of the spatial prepositions;
- an *English regex*: a regular expression (`re.compile`, `re.search`...) whose pattern spells a
  lower-case word of two letters or more outside its escapes and character classes, but in a module
  that reads machine text rather than words someone said (`MACHINE_TEXT`);
- a *reply sentence*: a string (an f-string included) of three words or more that starts with a
  capital and ends a sentence, outside `understanding/replies.py`, not a docstring, not what an
  exception or a log says;
- a *re-tokenisation*: a `.split()` on white space or a regex's `findall`/`split` in a stage of the
  understanding (understanding/, reference/, memory/, ask/), which reads the utterance object rather
  than its raw text; the tokeniser and the utterance object themselves, and what reads data rather
  than an utterance (the language's tables, the lexicon's synonyms file, the KB's ids in the
  snapshot), are not stages;
- a *clause splitter*: a function whose name says it cuts clauses, or a split on a conjunction;
- a *compared word*: one lower-case word (a string, or the one string of a row) compared with
  `==`, `!=`, `in` or `not in`, where it is not one of the code's own names.
"""

from __future__ import annotations

import ast
import re
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).parents[1]
_WORD = re.compile(r"[a-z]+(?:'[a-z]+)?(?: [a-z]+(?:'[a-z]+)?)*")
SPATIAL = frozenset(
    [
        "on",
        "in",
        "at",
        "under",
        "above",
        "below",
        "behind",
        "beside",
        "near",
        "inside",
        "onto",
        "into",
        "by",
        "next",
        "over",
        "underneath",
        "beneath",
        "between",
        "across",
        "through",
        "toward",
        "towards",
    ]
)
#: The code's own vocabulary: names it passes around, not words it hears (besides `Literal` values).
CODE_NAMES = frozenset(
    [
        "person",
        "zone",
        "robot",
        "thing",
        "place",
        "entity",
        "boolean",
        "integer",
        "number",
        "string",
        "enum",
        "object",
        "array",
        "null",
        "agent",
        "goal",
        "recipient",
        "other_data",
        "input",
        "locale",
        "support",
        "colour",
        "owner",
        "label",
        "id",
        "type",
        "name",
        "minimum",
        "maximum",
        "format",
        "title",
        "description",
        "properties",
        "required",
        "items",
        "default",
        "value",
        "values",
        "role",
        "content",
        "user",
        "assistant",
        "system",
        "text",
        "json",
    ]
)
#: Modules whose regexes read machine text, not words someone said, with what they read.
MACHINE_TEXT = {
    "dialogue/llm/llamabuild.py": "the CPU's flags (avx2, fma...)",
    "dialogue/trace/urlsecrets.py": "a URL's query keys (token, key, secret...)",
}
_REGEX_CALLS = frozenset(
    {"compile", "search", "match", "fullmatch", "sub", "subn", "split", "findall", "finditer"}
)
_SENTENCE = re.compile(r"^[A-Z][^\n]*\b[a-z]+\b[^\n]*[.?!]$")
_LETTERS = re.compile(r"[a-z]{2,}")
_CLAUSES = re.compile(r"(split|cut).*clause|clause.*(split|cut)|^_?clauses$")
_STAGES = ("dialogue/understanding/", "dialogue/reference/", "dialogue/memory/", "dialogue/ask/")
#: The tokeniser, and what reads the language's files (its phrases are data, not an utterance) or the
#: KB's (an id made readable: `cup_1` -> "cup 1").
_TOKENISERS = (
    "dialogue/reference/english.py",
    "dialogue/understanding/said.py",
    "dialogue/understanding/tables/",
    "dialogue/reference/synonyms.py",
    "dialogue/reference/snapshot.py",
)


@dataclass(frozen=True)
class Finding:
    kind: str
    path: str
    line: int
    text: str

    def __str__(self) -> str:
        return f"{self.path}:{self.line}: {self.kind}: {self.text}"


def _strings(node: ast.expr) -> list[str] | None:
    """The strings of a literal collection (a dict's keys and values), None if it is not one."""
    if (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Name)
        and node.func.id in ("frozenset", "set")
    ):
        return _strings(node.args[0]) if len(node.args) == 1 else None
    if isinstance(node, ast.Dict):
        items = [k for k in node.keys if k is not None] + list(node.values)
    elif isinstance(node, (ast.Set, ast.Tuple, ast.List)):
        # (a table of pairs is one table: its rows' strings are its own)
        items = [e for elt in node.elts for e in (elt.elts if isinstance(elt, ast.Tuple) else [elt])]
    else:
        return None
    return [i.value for i in items if isinstance(i, ast.Constant) and isinstance(i.value, str)]


def _literal_names(tree: ast.AST) -> set[str]:
    names: set[str] = set()
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Subscript)
            and isinstance(node.value, ast.Name)
            and node.value.id == "Literal"
        ):
            names.update(
                c.value
                for c in ast.walk(node.slice)
                if isinstance(c, ast.Constant) and isinstance(c.value, str)
            )
    return names


def _imported_literal_names(tree: ast.Module, root: Path) -> set[str]:
    """The `Literal` values of the names a module imports from the project's other modules: an
    alias (`Kind = Literal[...]`), or a class whose fields are typed with one (`Parse.act`)."""
    names: set[str] = set()
    for node in tree.body:
        if not isinstance(node, ast.ImportFrom) or not node.module or node.level:
            continue
        path = root / (node.module.replace(".", "/") + ".py")
        if not path.is_file():
            continue
        # each name the module defines, with the Literal values in its definition and the names
        # that definition refers to (a class's fields typed with an alias of the module)
        defined: dict[str, tuple[set[str], set[str]]] = {}
        for statement in ast.parse(path.read_text(encoding="utf-8")).body:
            targets: list[str] = []
            if isinstance(statement, ast.ClassDef):
                targets = [statement.name]
            elif isinstance(statement, ast.Assign):
                targets = [t.id for t in statement.targets if isinstance(t, ast.Name)]
            elif isinstance(statement, ast.AnnAssign) and isinstance(statement.target, ast.Name):
                targets = [statement.target.id]
            refers = {n.id for n in ast.walk(statement) if isinstance(n, ast.Name)}
            for target in targets:
                defined[target] = (_literal_names(statement), refers)
        for alias in node.names:
            values, refers = defined.get(alias.name, (set(), set()))
            names |= values
            names.update(v for r in refers & defined.keys() - {alias.name} for v in defined[r][0])
    return names


def _pattern(node: ast.Call) -> str | None:
    f = node.func
    if (
        isinstance(f, ast.Attribute)
        and isinstance(f.value, ast.Name)
        and f.value.id in ("re", "regex")
        and f.attr in _REGEX_CALLS
        and node.args
    ):
        first = node.args[0]
        if isinstance(first, ast.Constant) and isinstance(first.value, str):
            return first.value
        if isinstance(first, ast.JoinedStr):
            return "".join(
                v.value for v in first.values if isinstance(v, ast.Constant) and isinstance(v.value, str)
            )
    return None


def _english_in_pattern(pattern: str) -> list[str]:
    bare = re.sub(r"\\.", " ", pattern)  # escapes: \w, \b, \s...
    bare = re.sub(r"\[[^\]]*\]", " ", bare)  # character classes
    bare = re.sub(r"\(\?[a-zA-Z]+\)", " ", bare)  # inline flags
    bare = re.sub(r"\(\?P?<[^>]*>", " ", bare)  # group names
    return _LETTERS.findall(bare.lower() if "(?i)" in pattern else bare)


def _docstrings(tree: ast.AST) -> set[int]:
    ids: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                ids.add(id(first.value))
    return ids


def _unsaid(tree: ast.AST) -> set[int]:
    """Strings an exception, a log line, a warning, a field's description or an argument's help
    says: messages to developers and operators, not replies."""
    ids: set[int] = set()
    for node in ast.walk(tree):
        inside: list[ast.AST] = []
        if isinstance(node, (ast.Raise, ast.Assert)):
            inside = [node]
        elif isinstance(node, ast.Call):
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else ""
            if name in (
                "debug",
                "info",
                "warning",
                "error",
                "exception",
                "warn",
                "Field",
                "add_argument",
                "fail",
            ):
                inside = [node]
            inside += [
                k.value for k in node.keywords if k.arg in ("description", "help", "message", "reason")
            ]
        for part in inside:
            ids.update(id(n) for n in ast.walk(part) if isinstance(n, (ast.Constant, ast.JoinedStr)))
    return ids


def _sentence(node: ast.expr) -> str | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        text = node.value
    elif isinstance(node, ast.JoinedStr):
        text = "".join(str(v.value) if isinstance(v, ast.Constant) else "{}" for v in node.values)
    else:
        return None
    text = text.strip()
    return text if len(text.split()) >= 3 and _SENTENCE.match(text) else None


def _table(node: ast.AST, code: frozenset[str] | set[str], rows: set[int], rel: str) -> Iterator[Finding]:
    is_set_call = (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Name)
        and node.func.id in ("frozenset", "set")
    )
    if id(node) in rows or not isinstance(node, ast.expr) or (isinstance(node, ast.Call) and not is_set_call):
        return
    strings = _strings(node)
    if strings is None:
        return
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        rows.update(id(e) for e in node.elts if isinstance(e, ast.Tuple))
    elif isinstance(node, ast.Call):
        rows.update(id(a) for a in node.args)
    words = [s for s in strings if _WORD.fullmatch(s)]
    if len(words) >= 2 and not all(w in code for w in words):
        yield Finding(
            "word table", rel, node.lineno, ", ".join(words[:6]) + (" ..." if len(words) > 6 else "")
        )
        if len(set(words) & SPATIAL) >= 2:
            yield Finding("spatial table", rel, node.lineno, ", ".join(sorted(set(words) & SPATIAL)))


def _call(node: ast.Call, rel: str, stage: bool) -> Iterator[Finding]:
    pattern = _pattern(node)
    if pattern is not None and rel not in MACHINE_TEXT and _english_in_pattern(pattern):
        yield Finding("english regex", rel, node.lineno, pattern[:70])
    f = node.func
    if not isinstance(f, ast.Attribute):
        return
    on_re = isinstance(f.value, ast.Name) and f.value.id in ("re", "regex")
    tokenising = (f.attr == "split" and not node.args and not on_re) or f.attr in ("findall", "finditer")
    if stage and (tokenising or (on_re and f.attr == "split")):
        yield Finding("re-tokenisation", rel, node.lineno, ast.unparse(node)[:70])
    if f.attr == "split" and node.args:
        arg = node.args[-1] if on_re else node.args[0]
        if (
            isinstance(arg, ast.Constant)
            and isinstance(arg.value, str)
            and re.search(r"\b(and|then|but)\b", arg.value)
        ):
            yield Finding("clause splitter", rel, node.lineno, ast.unparse(node)[:70])


def _compared(node: ast.Compare, code: frozenset[str] | set[str], rel: str) -> Iterator[Finding]:
    """A word compared in code: `w == "not"`, `"of" in w`, `w[:1] == ["of"]` (a one-word row)."""
    if not any(isinstance(op, (ast.Eq, ast.NotEq, ast.In, ast.NotIn)) for op in node.ops):
        return
    for side in (node.left, *node.comparators):
        row = side.elts if isinstance(side, (ast.Tuple, ast.List)) and len(side.elts) == 1 else [side]
        for one in row:
            word = one.value if isinstance(one, ast.Constant) and isinstance(one.value, str) else ""
            if word not in code and _WORD.fullmatch(word) and " " not in word:
                yield Finding("compared word", rel, node.lineno, word)


def scan(path: Path, root: Path = ROOT) -> Iterator[Finding]:
    rel = path.relative_to(root).as_posix()
    tree = ast.parse(path.read_text(encoding="utf-8"))
    code = CODE_NAMES | _literal_names(tree) | _imported_literal_names(tree, root)
    skipped = _docstrings(tree) | _unsaid(tree)
    stage = rel.startswith(_STAGES) and not rel.startswith(_TOKENISERS)
    replies = not rel.endswith("understanding/replies.py")
    rows: set[int] = set()  # the rows of a table already counted
    for node in ast.walk(tree):
        yield from _table(node, code, rows, rel)
        if isinstance(node, ast.Call):
            yield from _call(node, rel, stage)
        if isinstance(node, ast.Compare):
            yield from _compared(node, code, rel)
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and _CLAUSES.search(node.name):
            yield Finding("clause splitter", rel, node.lineno, node.name)
        if replies and isinstance(node, (ast.Constant, ast.JoinedStr)) and id(node) not in skipped:
            if isinstance(node, ast.JoinedStr):
                skipped.update(id(v) for v in node.values)
            if (text := _sentence(node)) is not None:
                yield Finding("reply sentence", rel, node.lineno, text[:70])


def findings(root: Path = ROOT, package: str = "dialogue") -> list[Finding]:
    return [f for path in sorted((root / package).rglob("*.py")) for f in scan(path, root)]


def top_level_modules(root: Path = ROOT) -> int:
    return sum(1 for p in (root / "dialogue").glob("*.py") if p.name != "__init__.py")


def main(argv: list[str]) -> None:
    verbose = "-v" in argv
    roots = [a for a in argv if a != "-v"]
    root = Path(roots[0]) if roots else ROOT
    found = findings(root)
    kinds = (
        "word table",
        "spatial table",
        "english regex",
        "reply sentence",
        "re-tokenisation",
        "clause splitter",
        "compared word",
    )
    for kind in kinds:
        these = [f for f in found if f.kind == kind]
        modules = len({f.path for f in these})
        print(f"{kind:18} {len(these):4}  in {modules} modules")
        if verbose:
            for f in these:
                print("   ", f)
    print(f"{'dialogue/ top level':18} {top_level_modules(root):4}  modules")


if __name__ == "__main__":
    main(sys.argv[1:])
