"""A language as the offline understanding reads it: the data files of one `lang/<code>/` folder.

One folder per language, data only (the shape of Home Assistant's intents repository and of spaCy's
`lang/` folders): its words are never written in the code that reads them. A folder holds

    words.toml         closed-class words: determiners, pronouns, colours, numbers...
    prepositions.toml  one table of prepositions, each with what it introduces
    speech.toml        speech and chat forms: contractions, fillers, politeness, repairs, clauses
    social.toml        greetings and what is said with them
    frames.toml        the verb frames of requests
    requests.toml      the other words of requests: adjuncts, wishes, needs, compound and terse ones
    followups.toml     the words of answers to the robot's question
    questions.toml     the words of questions about the situation and about what people told
    statements.toml    the words of statements: names, ownership, places, likings
    ask.toml           the ask role's words: yes and no, numbers, cancelling and skipping
    replies.toml       what the robot says, as templates

and `lexicon.txt`, other ways of saying a name (dialogue.reference.synonyms). A file a language
does not have is a table it leaves empty.

A `Language` is read once (`Language.load(code)` for a packaged folder, `Language.read(folder)`
for any other) and passed to what reads words: the engine keeps one and its lexicons carry it.
Nothing is read at import time. A packaged folder is read once per process and shared: its files
are part of the installed package and never change while it runs, and every engine made (one per
case of an evaluation, one per test) once read and derived its tables again, half a second each.
"""

from __future__ import annotations

import tomllib
from collections.abc import Callable
from functools import cache, cached_property
from importlib import resources
from importlib.resources.abc import Traversable
from typing import Any, TypeVar

from pydantic import ValidationError

from dialogue.errors import DialogueError
from dialogue.understanding.tables.ask import AskWords
from dialogue.understanding.tables.base import Table
from dialogue.understanding.tables.followups import FollowupWords
from dialogue.understanding.tables.frames import FrameTable
from dialogue.understanding.tables.prepositions import Prepositions
from dialogue.understanding.tables.questions import QuestionWords
from dialogue.understanding.tables.requests import RequestWords
from dialogue.understanding.tables.social import SocialWords
from dialogue.understanding.tables.speech import SpeechWords
from dialogue.understanding.tables.statements import StatementWords
from dialogue.understanding.tables.words import ClosedWords

T = TypeVar("T")

#: The packaged languages' folders.
PACKAGE = "dialogue.understanding"


class LanguageError(DialogueError):
    """A language folder that cannot be read: missing, or a file that is not what it must be (the
    message names the file and the table)."""


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


def _replies(folder: Traversable) -> dict[str, dict[str, Any]]:
    file = folder / "replies.toml"
    if not file.is_file():
        return {}
    try:
        sections = tomllib.loads(file.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise LanguageError(f"{file}: not TOML: {exc}") from None
    wrong = [name for name, section in sections.items() if not isinstance(section, dict)]
    if wrong:
        raise LanguageError(f"{file}: {wrong[0]!r} is no section of templates")
    return sections


class Language:
    """The tables of one language folder, read once."""

    def __init__(self, folder: Traversable, code: str) -> None:
        if not folder.is_dir():
            raise LanguageError(f"no language folder {folder}")
        self.code = code
        self.words: ClosedWords = _table(folder, "words", ClosedWords)
        self.prepositions: Prepositions = _table(folder, "prepositions", Prepositions)
        self.speech: SpeechWords = _table(folder, "speech", SpeechWords)
        self.social: SocialWords = _table(folder, "social", SocialWords)
        self.requests: RequestWords = _table(folder, "requests", RequestWords)
        self.frames: FrameTable = _table(folder, "frames", FrameTable)
        self.followups: FollowupWords = _table(folder, "followups", FollowupWords)
        self.questions: QuestionWords = _table(folder, "questions", QuestionWords)
        self.statements: StatementWords = _table(folder, "statements", StatementWords)
        self.ask: AskWords = _table(folder, "ask", AskWords)
        #: What the robot says, as templates by section (dialogue.understanding.replies renders them).
        self.replies: dict[str, dict[str, Any]] = _replies(folder)
        lexicon = folder / "lexicon.txt"
        #: Other ways of saying a name (dialogue.reference.synonyms parses it).
        self.lexicon = lexicon.read_text(encoding="utf-8") if lexicon.is_file() else ""
        self._derived: dict[Callable[[Language], Any], Any] = {}

    def derived(self, make: Callable[[Language], T]) -> T:
        """What another module derives from this language's tables (its synonyms parsed, its verb
        index), made on first use and kept with the language (two threads may both make it once)."""
        # (a subscript, no other call: every stage of a turn asks for its tables, ~90 times a turn)
        try:
            made: T = self._derived[make]
        except KeyError:
            made = self._derived[make] = make(self)
        return made

    @classmethod
    def load(cls, code: str = "en") -> Language:
        """A packaged language (`lang/<code>/` of this package), read on first use and shared."""
        return _packaged(code)

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


@cache
def _packaged(code: str) -> Language:
    return Language(resources.files(PACKAGE) / "lang" / code, code)
