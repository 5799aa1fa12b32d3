"""The tables of a language folder's files, as typed models (dialogue.understanding.language reads
them): one model per file, a table a file leaves out empty, any other key refused."""

from __future__ import annotations

import re
from collections.abc import Sequence
from functools import cached_property
from typing import Annotated, Any, Literal

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field

Words = tuple[str, ...]


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


def _phrase(value: Any) -> Any:
    """ "what is" -> ("what", "is")."""
    return tuple(value.split()) if isinstance(value, str) else value


WordSet = Annotated[frozenset[str], BeforeValidator(_words)]
WordList = Annotated[tuple[str, ...], BeforeValidator(_words)]
Phrases = Annotated[tuple[Words, ...], BeforeValidator(_phrases)]
PhraseSet = Annotated[frozenset[Words], BeforeValidator(_phrases)]
Phrase = Annotated[Words, BeforeValidator(_phrase)]
#: A regular expression (flags inline: "(?i)").
Pattern = Annotated[re.Pattern[str], BeforeValidator(lambda v: re.compile(v) if isinstance(v, str) else v)]


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
    np_start: WordSet = frozenset()
    owners: dict[str, str] = {}
    wh: WordSet = frozenset()
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


class ClauseWords(Table):
    """`speech.toml` [clauses]: where a run-on utterance is cut into clauses."""

    asks: Phrases = ()
    indefinite: WordSet = frozenset()
    subjects: WordSet = frozenset()
    auxiliaries: WordSet = frozenset()
    takes_clause: WordSet = frozenset()
    telling: WordSet = frozenset()
    reasons: WordSet = frozenset()
    hedges: WordSet = frozenset()
    describing: Phrases = ()
    thinking: Phrases = ()
    put: WordSet = frozenset()


class SpellingWords(Table):
    """`speech.toml` [spelling]: how a typo is found."""

    asked: WordSet = frozenset()
    keyboard: tuple[str, ...] = ()
    offsets: tuple[float, ...] = ()


class SpeechWords(Table):
    """`speech.toml`: speech and chat forms."""

    fillers: WordSet = frozenset()
    filler_pairs: PhraseSet = frozenset()
    asking: WordSet = frozenset()
    lead_fillers: WordSet = frozenset()
    repairs: Phrases = ()
    polite_prefixes: Phrases = ()
    robot_suffixes: Phrases = ()
    polite_suffixes: Phrases = ()
    tags: Phrases = ()
    not_vocative: WordSet = frozenset()
    auxiliaries: WordSet = frozenset()
    homophones: Phrases = ()
    not_nouns: WordSet = frozenset()
    numbering: WordSet = frozenset()
    my_after: WordSet = frozenset()
    wishing: WordSet = frozenset()
    preposition_slips: dict[str, str] = {}
    contractions: dict[str, Phrase] = {}
    chat: dict[str, Phrase] = {}
    clauses: ClauseWords = ClauseWords()
    spelling: SpellingWords = SpellingWords()

    @cached_property
    def written(self) -> dict[str, Words]:
        """Every written form read as other words: contractions, with or without the apostrophe,
        and chat."""
        return {**self.contractions, **self.chat}

    @cached_property
    def all_polite_suffixes(self) -> Phrases:
        """The politeness at the end of a request: the robot's, the others, and the tags ("the yellow
        one mate", "over here love")."""
        return (*self.robot_suffixes, *self.polite_suffixes, *self.tags)


class ConstructionWords(Table):
    """`requests.toml` [constructions]: the words of the small constructions."""

    not_things: WordSet = frozenset()
    shown: WordSet = frozenset()
    subjects: WordSet = frozenset()
    verbs_of_any: WordSet = frozenset()


class CompoundWords(Table):
    """`requests.toml` [compound]: where a compound request is cut."""

    conjunctions: WordSet = frozenset()
    bare_verbs: WordSet = frozenset()
    serial: WordSet = frozenset()
    greeting: PhraseSet = frozenset()
    object_start: WordSet = frozenset()
    no_cut_after: WordSet = frozenset()
    a_bit: WordSet = frozenset()


class TerseWords(Table):
    """`requests.toml` [terse]: terse requests."""

    subjects: WordSet = frozenset()


class ReferentWords(Table):
    """`requests.toml` [referents]: the words a role's phrase is grounded with."""

    relational: WordSet = frozenset()
    accounted: WordSet = frozenset()
    every: WordSet = frozenset()
    some: WordSet = frozenset()


class RequestWords(Table):
    """`requests.toml`: the words of requests."""

    here: Phrases = ()
    there: Phrases = ()
    adjuncts: Phrases = ()
    away: Phrases = ()
    durations: Phrases = ()
    while_: WordSet = Field(default=frozenset(), validation_alias="while")
    time_conjunctions: WordSet = frozenset()
    their_subjects: WordSet = frozenset()
    polite_if: Phrases = ()
    if_modals: WordSet = frozenset()
    halts: WordSet = frozenset()
    manner: WordSet = frozenset()
    wants: Phrases = ()
    want_verbs: WordSet = frozenset()
    their_wants: Phrases = ()
    wishers: WordSet = frozenset()
    not_wishers: WordSet = frozenset()
    intensifiers: WordSet = frozenset()
    done: WordSet = frozenset()
    goes: Phrases = ()
    goes_particles: WordSet = frozenset()
    terse_motion: WordSet = frozenset()
    everyone: PhraseSet = frozenset()
    stop_filler: WordSet = frozenset()
    activity_filler: WordSet = frozenset()
    results: WordSet = frozenset()
    no_intent_verbs: WordSet = frozenset()
    needs: dict[str, str] = {}
    purposes: dict[str, Phrase] = {}
    constructions: ConstructionWords = ConstructionWords()
    compound: CompoundWords = CompoundWords()
    terse: TerseWords = TerseWords()
    referents: ReferentWords = ReferentWords()

    @cached_property
    def all_adjuncts(self) -> Phrases:
        """Every phrase that says how or when: the adjuncts, the durations, where not to be."""
        return (*self.adjuncts, *self.durations, *self.away)

    def purpose(self, words: Words) -> Words | None:
        """The kind of thing "to eat", "to cut this with" (the words after "something") name, if any."""
        return self.purposes.get(words[1]) if len(words) > 1 and words[0] == "to" else None


class SocialWords(Table):
    """`social.toml`: greetings and what is said with them."""

    greetings: Phrases = ()
    attention: PhraseSet = frozenset()
    social: PhraseSet = frozenset()

    @cached_property
    def greetings_longest_first(self) -> Phrases:
        """The greetings, longest first: "hello there" before "hello"."""
        return tuple(sorted(self.greetings, key=len, reverse=True))


class FrameRow(Table):
    """`frames.toml` [[frame]]: one verb frame, as the file says it (dialogue.understanding.requests.frames
    reads it into a `Frame`)."""

    model_config = ConfigDict(frozen=True, extra="forbid", alias_generator=lambda n: n.replace("_", "-"))

    verbs: str
    intent: str | None = None
    direct: str | None = None
    slots: dict[str, str] = {}
    particles: str = ""
    here: str | None = None
    there_only: bool = False
    dative: Literal["me", "any", "before"] | None = None
    only: str | None = None
    requires: tuple[str, ...] = ()
    defaults: dict[str, Phrase] = {}
    whole: bool = False
    text: Literal["verb", "activity", "doing", "stopping"] | None = None
    named: str | None = None
    special: str | None = None
    serial: bool = False


class FrameTable(Table):
    """`frames.toml`: the verb frames, their groups of words, the constructions tried before them."""

    constructions: tuple[str, ...] = ()
    groups: dict[str, str] = {}
    frame: tuple[FrameRow, ...] = ()


class FollowupWords(Table):
    """`followups.toml`: the words of answers to the robot's question."""

    interjections: WordSet = frozenset()
    one: WordSet = frozenset()
    offers: Phrases = ()
    offers_a_thing: Phrases = ()
    swapped: dict[str, str] = {}
    confirms: Phrases = ()
    accepting: WordSet = frozenset()
    yes: WordSet = frozenset()
    yes_phrases: Phrases = ()
    no: dict[str, str] = {}
    other: WordSet = frozenset()
    correcting: Phrases = ()
    softening: WordSet = frozenset()
    emphasis: WordSet = frozenset()


class LikingWords(Table):
    """`statements.toml` [likings]: "I like tea", "I'm fond of tea", "tea is my favourite"."""

    intensifiers: WordSet = frozenset()
    like: WordSet = frozenset()
    hate: WordSet = frozenset()
    favourite: WordSet = frozenset()
    over: WordSet = frozenset()
    happenings: WordSet = frozenset()
    appraised: PhraseSet = frozenset()
    clause: WordSet = frozenset()
    leads: dict[str, str] = {}


class NameWords(Table):
    """`statements.toml` [names]: which words can be a person's name."""

    not_names: WordSet = frozenset()


class StatementWords(Table):
    """`statements.toml`: the words of statements."""

    clauses: Pattern = re.compile(r"(?!)")
    leads: WordSet = frozenset()
    by_the_way: Phrase = ()
    asking: WordSet = frozenset()
    friends: WordSet = frozenset()
    put: WordSet = frozenset()
    be: WordSet = frozenset()
    polite: PhraseSet = frozenset()
    no: PhraseSet = frozenset()
    name_asked: tuple[str, ...] = ()
    name_leads_surely: Phrases = ()
    name_leads: Phrases = ()
    pointed: PhraseSet = frozenset()
    greeting_topics: Phrases = ()
    likings: LikingWords = LikingWords()
    names: NameWords = NameWords()


class SituationQuestionWords(Table):
    """`questions.toml` [situation]: the words of questions about the situation."""

    sees: Phrases = ()
    where_leads: Phrases = ()
    on_glue: WordSet = frozenset()
    who_not_a_name: WordSet = frozenset()
    see_words: WordSet = frozenset()
    colour_words: WordSet = frozenset()
    indirect: Phrases = ()
    be: WordSet = frozenset()
    someone: WordSet = frozenset()
    else_: WordSet = Field(default=frozenset(), validation_alias="else")
    owners: WordSet = frozenset()
    nearby: WordSet = frozenset()
    others: WordSet = frozenset()
    there: WordSet = frozenset()
    asking_verbs: WordSet = frozenset()
    asked_subjects: WordSet = frozenset()
    count_tail: WordSet = frozenset()
    someone_said: WordSet = frozenset()


class ToldQuestionWords(Table):
    """`questions.toml` [told]: the words of questions about what people told."""

    like: WordSet = frozenset()
    hate: WordSet = frozenset()
    who_am_i: PhraseSet = frozenset()
    tail: WordSet = frozenset()
    pronoun_of: dict[str, Phrase] = {}


class QuestionWords(Table):
    """`questions.toml`: the words of questions."""

    situation: SituationQuestionWords = SituationQuestionWords()
    told: ToldQuestionWords = ToldQuestionWords()


class AskAnswerWords(Table):
    """`ask.toml` [answers]: how an answer to the ask role's form is read."""

    cancel: Pattern = re.compile(r"(?!)")
    skip: Pattern = re.compile(r"(?!)")
    correction: WordSet = frozenset()
    split: Pattern = re.compile(r"(?!)")


class AskWords(Table):
    """`ask.toml`: the ask role's words."""

    yes: WordSet = frozenset()
    no: WordSet = frozenset()
    not_negators: WordSet = frozenset()
    lead_ins: WordSet = frozenset()
    self_: WordSet = Field(default=frozenset(), validation_alias="self")
    ordinals: dict[str, int] = {}
    lead_in_text: Pattern = re.compile("")
    question_back: Pattern = re.compile(r"(?!)")
    number: Pattern = re.compile(r"(?<![\w.])(-)?(\d+(?:\.\d+)?)(?![\w]|\.\d)")
    pronoun_one: Pattern = re.compile(r"(?!)")
    thousands: Pattern = re.compile(r"(?!)")
    half: Pattern = re.compile(r"(?!)")
    field_value: Pattern = re.compile(r":")
    boolean_phrases: dict[str, bool] = {}
    answers: AskAnswerWords = AskAnswerWords()
