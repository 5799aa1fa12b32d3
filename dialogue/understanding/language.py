"""A language as the offline understanding reads it: the data files of one `lang/<code>/` folder.

One folder per language, data only (the shape of Home Assistant's intents repository and of spaCy's
`lang/` folders): its words are never written in the code that reads them. A folder holds

    words.toml         closed-class words: determiners, pronouns, colours, numbers...
    prepositions.toml  one table of prepositions, each with what it introduces

and `lexicon.txt`, other ways of saying a name (dialogue.reference.synonyms). A file a language
does not have is a table it leaves empty.

A `Language` is read once (`Language.load(code)` for a packaged folder, `Language.read(folder)`
for any other) and passed to what reads words: the engine keeps one and its lexicons carry it.
Nothing is read at import time, and nothing keeps a language behind the caller's back.
"""

from __future__ import annotations

import tomllib
from collections.abc import Callable, Sequence
from functools import cached_property
from importlib import resources
from importlib.resources.abc import Traversable
from typing import Annotated, Any, TypeVar, cast

from pydantic import BaseModel, BeforeValidator, ConfigDict, ValidationError

from dialogue.errors import DialogueError

Words = tuple[str, ...]
T = TypeVar("T")

#: The packaged languages' folders.
PACKAGE = "dialogue.understanding"


class LanguageError(DialogueError):
    """A language folder that cannot be read: missing, or a file that is not what it must be (the
    message names the file and the table)."""


def _words(value: Any) -> Any:
    """ "a b c" (or ["a", "b"]) -> the words."""
    if isinstance(value, str):
        return value.split()
    return value


def _phrases(value: Any) -> Any:
    """ "a b|c" (or ["a b", "c"]) -> (("a", "b"), ("c",)), in order."""
    if isinstance(value, str):
        value = value.split("|")
    if isinstance(value, list):
        return [tuple(p.split()) if isinstance(p, str) else p for p in value]
    return value


WordSet = Annotated[frozenset[str], BeforeValidator(_words)]
WordList = Annotated[tuple[str, ...], BeforeValidator(_words)]
Phrases = Annotated[tuple[Words, ...], BeforeValidator(_phrases)]


class Table(BaseModel):
    """The tables of one file; a table the file leaves out is empty."""

    model_config = ConfigDict(frozen=True, extra="forbid")


class HeadNounWords(Table):
    """`words.toml` [head_noun]: the words of a noun phrase's head, read by dialogue.reference.headnoun."""

    qualifiers: WordSet = frozenset()
    skipped: WordSet = frozenset()
    clause_words: WordSet = frozenset()
    new_phrase: WordSet = frozenset()
    several: WordSet = frozenset()


class ClosedWords(Table):
    """`words.toml`: closed-class words."""

    determiners: WordSet = frozenset()
    pronouns: WordSet = frozenset()
    personal: WordSet = frozenset()
    neuter: WordSet = frozenset()
    possessives: WordSet = frozenset()
    me: WordSet = frozenset()
    colours: WordSet = frozenset()
    positions: WordSet = frozenset()
    parts: WordSet = frozenset()
    containers: WordSet = frozenset()
    compound_heads: WordSet = frozenset()
    measures: WordSet = frozenset()
    many: WordSet = frozenset()
    relativisers: WordSet = frozenset()
    titles: Phrases = ()
    numbers: WordSet = frozenset()
    units: WordList = ()
    tens: WordList = ()
    function_words: WordSet = frozenset()
    glue: WordSet = frozenset()
    core_end: WordSet = frozenset()
    not_said: WordSet = frozenset()
    head_noun: HeadNounWords = HeadNounWords()

    @cached_property
    def spoken_numbers(self) -> dict[str, Words]:
        """Numbers below a hundred as said in words ("7" -> ("seven",), "21" -> ("twenty", "one"))."""
        units = self.units
        tens = {str(20 + 10 * t + u): (w, units[u]) if u else (w,)
                for t, w in enumerate(self.tens) for u in range(10)}  # fmt: skip
        return {**{str(n): (w,) for n, w in enumerate(units)}, **tens}

    @cached_property
    def written(self) -> dict[Words, str]:
        return {words: digits for digits, words in self.spoken_numbers.items()}

    @cached_property
    def any_function_word(self) -> frozenset[str]:
        """Closed-class words in general (pronouns, prepositions, conjunctions, auxiliaries, number
        words): always words of the language, whatever a lexicon of content words says."""
        return self.numbers | self.function_words

    def other_numbers(self, words: Sequence[str]) -> Words | None:
        """The words with each number below a hundred written the other way: "plot 7" -> "plot
        seven", "table nine" -> "table 9", "gate twenty one" -> "gate 21"; None when they have no
        number."""
        written, spoken = self.written, self.spoken_numbers
        out: list[str] = []
        i = 0
        while i < len(words):
            pair, one = tuple(words[i : i + 2]), (words[i],)
            if len(pair) == 2 and pair in written:
                out.append(written[pair])
                i += 2
                continue
            out.extend(spoken.get(words[i]) or ((written[one],) if one in written else one))
            i += 1
        return tuple(out) if out != list(words) else None


class Preposition(Table):
    """One row of the preposition table (its columns are described in prepositions.toml)."""

    model_config = ConfigDict(frozen=True, extra="forbid", alias_generator=lambda n: n.replace("_", "-"))

    uses: WordSet = frozenset()
    said_back: str | None = None
    relations: frozenset[str] = frozenset()
    evidence: frozenset[str] = frozenset()
    states: str | None = None
    says: str | None = None
    reads_as: str | None = None


class Prepositions(Table):
    """`prepositions.toml`: one table of prepositions (single words and phrases), in order."""

    prepositions: dict[str, Preposition] = {}

    def having(self, use: str) -> tuple[Words, ...]:
        """The prepositions that have a use, as phrases, in the table's order."""
        return tuple(tuple(p.split()) for p, row in self.prepositions.items() if use in row.uses)

    def words(self, use: str) -> frozenset[str]:
        """The one-word prepositions that have a use."""
        return frozenset(p[0] for p in self.having(use) if len(p) == 1)

    def longest_first(self, use: str) -> tuple[Words, ...]:
        """The prepositions that have a use, longest first (then in the table's order): the first
        that a text starts with is the longest it starts with ("on top of" before "on")."""
        return tuple(sorted(self.having(use), key=len, reverse=True))

    def row(self, words: Sequence[str]) -> Preposition | None:
        return self.prepositions.get(" ".join(words))

    def column(self, name: str) -> dict[str, Any]:
        """Each preposition that has a value in a column, with it ("said_back": "beside" -> "next to")."""
        return {p: v for p, row in self.prepositions.items() if (v := getattr(row, name))}


def _table(folder: Traversable, name: str, model: type[Table]) -> Any:
    file = folder / f"{name}.toml"
    if not file.is_file():
        return model()
    try:
        return model.model_validate(tomllib.loads(file.read_text(encoding="utf-8")))
    except tomllib.TOMLDecodeError as exc:
        raise LanguageError(f"{file}: not TOML: {exc}") from None
    except ValidationError as exc:
        wrong = "; ".join(f"{'.'.join(map(str, e['loc']))}: {e['msg']}" for e in exc.errors())
        raise LanguageError(f"{file}: {wrong}") from None


class Language:
    """The tables of one language folder, read once."""

    def __init__(self, folder: Traversable, code: str) -> None:
        if not folder.is_dir():
            raise LanguageError(f"no language folder {folder}")
        self.code = code
        self.words: ClosedWords = _table(folder, "words", ClosedWords)
        self.prepositions: Prepositions = _table(folder, "prepositions", Prepositions)
        lexicon = folder / "lexicon.txt"
        #: Other ways of saying a name (dialogue.reference.synonyms parses it).
        self.lexicon = lexicon.read_text(encoding="utf-8") if lexicon.is_file() else ""
        self._derived: dict[Callable[[Language], Any], Any] = {}

    def derived(self, make: Callable[[Language], T]) -> T:
        """What another module derives from this language's tables (its synonyms parsed, its verb
        index), made on first use and kept with the language (two threads may both make it once)."""
        if make not in self._derived:
            self._derived[make] = make(self)
        return cast(T, self._derived[make])

    @classmethod
    def load(cls, code: str = "en") -> Language:
        """A packaged language (`lang/<code>/` of this package)."""
        return cls(resources.files(PACKAGE) / "lang" / code, code)

    @classmethod
    def read(cls, folder: Traversable, code: str | None = None) -> Language:
        """The language of any folder (its name is its code unless one is given)."""
        return cls(folder, code or folder.name)

    def __repr__(self) -> str:
        return f"Language({self.code!r})"

    @cached_property
    def support(self) -> frozenset[str]:
        """Prepositions whose object is where a thing is kept: its support or its zone ("the cup on the
        table")."""
        return self.prepositions.words("support")

    @cached_property
    def locative(self) -> frozenset[str]:
        """Prepositions that say where: after one, a mention is a place ("put it on the shelf")."""
        return self.prepositions.words("locative")

    @cached_property
    def glue(self) -> frozenset[str]:
        """Words allowed inside a phrase without qualifying anything: the determiners and the glue."""
        return self.words.determiners | self.words.glue

    @cached_property
    def modifier_start(self) -> frozenset[str]:
        """Words that end the core of a noun phrase and start a modifier ("the box *on* the table",
        "the coke *that* is in the kitchen", "a glass *of* water")."""
        return self.prepositions.words("modifier") | self.words.relativisers
