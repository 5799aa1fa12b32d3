"""The model of `requests.toml`: the other words of requests."""

from __future__ import annotations

from functools import cached_property

from pydantic import Field

from dialogue.understanding.tables.base import (
    Phrase,
    Phrases,
    PhraseSet,
    Table,
    Words,
    WordSet,
)


class ConstructionWords(Table):
    """`requests.toml` [constructions]: the words of the small constructions."""

    not_things: WordSet = frozenset()
    shown: WordSet = frozenset()
    finding_the_way: Phrases = ()
    subjects: WordSet = frozenset()
    verbs_of_any: WordSet = frozenset()
    available: Phrases = ()
    available_ends: WordSet = frozenset()
    anything: WordSet = frozenset()
    someone_is: WordSet = frozenset()
    needy: PhraseSet = frozenset()
    going_wants: PhraseSet = frozenset()
    going_verbs: WordSet = frozenset()
    speakers: WordSet = frozenset()
    a_hand: Phrase = ()
    a_hand_particles: WordSet = frozenset()
    enough_lead: Phrase = ()
    enough: WordSet = frozenset()
    helped_to: Phrases = ()
    copulas: WordSet = frozenset()
    subject_ends: WordSet = frozenset()
    quote_skipped: WordSet = frozenset()
    goodbyes: WordSet = frozenset()
    goodbye: str = ""
    telling: WordSet = frozenset()
    told_marks: Phrases = ()
    groups: WordSet = frozenset()
    needs_doing: WordSet = frozenset()
    doing: str = ""
    after: WordSet = frozenset()
    after_ends: Phrases = ()
    asked_whether: WordSet = frozenset()
    asked_of: WordSet = frozenset()
    asked_not_after: WordSet = frozenset()
    asked_as_you: dict[str, Phrase] = {}
    asked_plain: Phrase = ()


class CompoundWords(Table):
    """`requests.toml` [compound]: where a compound request is cut."""

    conjunctions: WordSet = frozenset()
    bare_verbs: WordSet = frozenset()
    serial: WordSet = frozenset()
    fetching: WordSet = frozenset()
    greeting: PhraseSet = frozenset()
    object_start: WordSet = frozenset()
    no_cut_after: WordSet = frozenset()
    a_bit: WordSet = frozenset()


class TerseWords(Table):
    """`requests.toml` [terse]: terse requests, and the requests they are read as (templates)."""

    subjects: WordSet = frozenset()
    moving: str = ""
    going: str = ""
    putting: str = ""
    handed_me: str = ""
    handed: str = ""


class ReferentWords(Table):
    """`requests.toml` [referents]: the words a role's phrase is grounded with."""

    relational: WordSet = frozenset()
    accounted: WordSet = frozenset()
    owner: WordSet = frozenset()
    beneficiary: WordSet = frozenset()
    every: WordSet = frozenset()
    some: WordSet = frozenset()
    some_glue: WordSet = frozenset()
    person_objects: WordSet = frozenset()
    pronoun_glue: WordSet = frozenset()
    placed_pronouns: WordSet = frozenset()
    pronoun_like: WordSet = frozenset()


class RequestWords(Table):
    """`requests.toml`: the words of requests."""

    here: Phrases = ()
    there: Phrases = ()
    somewhere: WordSet = frozenset()
    brought_here: PhraseSet = frozenset()
    said_there: PhraseSet = frozenset()
    staying: WordSet = frozenset()
    stays: PhraseSet = frozenset()
    adjuncts: Phrases = ()
    away: Phrases = ()
    durations: Phrases = ()
    while_: WordSet = Field(default=frozenset(), validation_alias="while")
    time_conjunctions: WordSet = frozenset()
    absent_speakers: WordSet = frozenset()
    absences: WordSet = frozenset()
    their_subjects: WordSet = frozenset()
    polite_if: Phrases = ()
    if_modals: WordSet = frozenset()
    conditions: Phrases = ()
    arrivals: Phrases = ()
    not_conditions: WordSet = frozenset()
    your_time: WordSet = frozenset()
    halts: WordSet = frozenset()
    negators: WordSet = frozenset()
    negation: Phrase = ()
    manner: WordSet = frozenset()
    wants: Phrases = ()
    own_wants: Phrases = ()
    own: WordSet = frozenset()
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
    activity_anaphora: WordSet = frozenset()
    results: WordSet = frozenset()
    no_intent_verbs: WordSet = frozenset()
    fixtures: WordSet = frozenset()
    hanging: WordSet = frozenset()
    abilities: Phrases = ()
    performances: Phrases = ()
    skill_verbs: WordSet = frozenset()
    skills: Phrases = ()
    starting: WordSet = frozenset()
    placing_carriers: WordSet = frozenset()
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
