"""The language's words the grammar of requests reads (dialogue.understanding.requests.commands and
requests.timing), gathered once per language (`Language.derived`)."""

from __future__ import annotations

from dialogue.reference.english import Words
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Act
from dialogue.understanding.requests.frames import Special, constructions
from dialogue.understanding.tables.prefixes import Prefixes


class Grammar:
    """The language's words a request is read with (made once per language)."""

    def __init__(self, lang: Language) -> None:
        closed, said, social = lang.words, lang.requests, lang.social
        self.determiners = closed.determiners
        self.function_words = closed.any_function_word
        self.many = closed.many
        self.me = closed.me
        self.modifier_start = lang.modifier_start
        self.personal = closed.personal
        self.np_start = closed.np_start
        self.adjuncts = said.all_adjuncts
        #: The same by their first word, in their order: a word is compared with the few it starts.
        self.adjuncts_by_first: dict[str, tuple[Words, ...]] = {}
        for phrase in self.adjuncts:
            self.adjuncts_by_first[phrase[0]] = (*self.adjuncts_by_first.get(phrase[0], ()), phrase)
        self.away = frozenset(said.away)
        self.durations = Prefixes(said.durations)
        self.halts = said.halts
        self.negators = said.negators
        self.negation = said.negation
        self.if_modals = said.if_modals
        self.conditions = Prefixes(said.conditions)
        self.not_conditions = said.not_conditions
        self.your_time = said.your_time
        self.manner = said.manner
        self.polite_if = Prefixes(said.polite_if)
        self.results = said.results
        self.their_subjects = said.their_subjects
        self.time_conjunctions = said.time_conjunctions
        self.while_ = said.while_
        self.absent_speakers = said.absent_speakers
        self.absences = said.absences
        self.purpose = said.purpose
        self.greetings = Prefixes(social.greetings_longest_first)
        #: "do the same with the blue one": a follow-up, no request of its own.
        self.again = Prefixes(lang.followups.again)
        self.attention = social.attention
        self.social = social.social
        self.thanks = social.thanks
        self.thank_you = social.thank_you
        self.after_no = social.after_no
        self.welcome_back = social.welcome_back
        #: Talk the robot answers in words alone, each act by its phrases.
        self.talk: tuple[tuple[Act, frozenset[tuple[str, ...]]], ...] = (
            ("farewell", social.farewells), ("abilities", social.abilities), ("joke", social.jokes))
        self.goal_particles = lang.prepositions.words("goal-particle")
        self.paths = lang.prepositions.words("path")
        #: Two-word prepositions read as one word, so that their "to" is never taken for a
        #: recipient's ("next to": "beside").
        self.joined = lang.prepositions.phrase_column("reads_as")
        #: Prepositions that never end a request as a particle: a role said with one and nothing
        #: after it was cut short ("give it to"), where "come in", "hold on" end with a particle.
        self.cut_short = lang.prepositions.words("cut-short")
        #: Pointing words and what they point at, longest first: the speaker, or the place just
        #: spoken of.
        self.pointing = sorted([(p, ("me",)) for p in said.here] + [(p, ("there",)) for p in said.there],
                               key=lambda p: -len(p[0]))  # fmt: skip
        self.somewhere = said.somewhere
        self.own_phrase = closed.np_start | {"her"}
        self.constructions: tuple[Special, ...] = constructions(lang)
