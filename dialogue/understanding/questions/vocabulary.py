"""The words the grammar of questions about the situation reads (dialogue.understanding.questions.grammar),
gathered once per language."""

from __future__ import annotations

from dialogue.understanding.language import Language
from dialogue.understanding.tables.prefixes import Prefixes


class QuestionWords:
    """The language's words of questions about the situation (made once per language)."""

    def __init__(self, lang: Language) -> None:
        said, prepositions = lang.questions.situation, lang.prepositions
        #: The language itself, for the steps that read its other tables (presence).
        self.lang = lang
        self.wh = lang.words.wh
        self.colours = lang.words.colours
        self.sees = Prefixes(said.sees)
        self.not_seen_before = said.not_seen_before
        self.where_leads = said.where_leads
        self.on_glue = said.on_glue
        self.who_not_a_name = said.who_not_a_name
        self.who_pointing = said.who_pointing
        #: Verbs of how a thing is placed ("lying", "sitting") between "is" and where.
        self.posture = said.posture
        self.count = Prefixes(said.count)
        self.who_sees = said.who_sees | said.who_not_a_name | said.else_
        self.see_words = said.see_words
        self.colour_words = said.colour_words
        self.locatives = prepositions.having("asked-on")
        #: Relations beside support and zone a "what is ... X" question may ask about.
        self.near = prepositions.having("asked-near")
        #: Leads of an indirect question: "do you know where the keys are", "any idea where the
        #: toolbox is".
        self.indirect = Prefixes(said.indirect)
        self.describe, self.described = Prefixes(said.describe), said.described
        self.determiners = lang.words.determiners
        self.be = said.be
        self.someone = said.someone
        self.else_ = said.else_
        self.owners = said.owners
        self.nearby = said.nearby
        self.others = said.others
        #: Words that ask whether someone is there ("is Maria about?").
        self.there = said.there
        self.there_after = said.there_after
        #: The verb of a question's own clause after what it counts ("how many cans *have* we got").
        self.asking_verbs = said.asking_verbs
        self.asked_subjects = said.asked_subjects
        #: Words after a counted thing that only say where or in all ("here", "left", "altogether").
        self.count_tail = said.count_tail
        self.place_starts = prepositions.words("place-start")
        self.purpose = lang.requests.purpose
        self.available = frozenset(lang.requests.constructions.available)
        self.seen_by_anyone = Prefixes(said.seen_by_anyone)
        self.placing = said.placing
        self.asker = said.asker
        self.gone = said.gone
        self.rooms = said.rooms
        self.name_of = Prefixes(said.name_of)
        self.show_me, self.tell_me, self.how_many = said.show_me, said.tell_me, said.how_many
        self.belong_to, self.in_front, self.are_you = said.belong_to, said.in_front, said.are_you
        self.what_heads = said.what_heads
        self.anything = said.anything
        #: "is" and "are" alone (`be` has their past too).
        self.is_are = said.is_are
        self.social_how = Prefixes(said.social_how)
        #: Where "who is at X" asks about.
        self.who_at = prepositions.words("who-at")
        self.count_glue, self.count_after = said.count_glue, said.count_after
        self.seeing_aux, self.you_see, self.not_which_see = said.seeing_aux, said.you_see, said.not_which_see
        self.name_words, self.not_what_is = said.name_words, said.not_what_is
        self.front_of = said.front_of
        self.does = said.does
        self.demonstratives = lang.words.demonstratives
        self.got_to, self.did, self.went = said.got_to, said.did, said.went
        self.where_am_i = said.where_am_i
        self.where_tail = said.where_tail
        self.whoever = said.whoever
