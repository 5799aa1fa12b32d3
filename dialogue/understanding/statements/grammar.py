"""The rules' grammar of statements: what a person tells the robot, as facts of the answer schema.

    I'm Bob · my name is Bob · call me Bob · no, it's Rob      -> <speaker> name "Bob"
    this is Maria (exactly one person present has no name)    -> <that person> name "Maria"
    the red mug is mine · that phone belongs to Ines          -> <thing> belongsTo <person>
    the keys are in the drawer · I left my glasses on the sofa -> <thing> isIn / isOn <place>
    I like tea · Alice hates coffee · I don't like the radio  -> <person> likes / dislikes <kind or thing>

Likings are read by dialogue.understanding.statements.likings, the phrases grounded by
dialogue.understanding.statements.clause (the reader this grammar is built on). A turn is claimed
only when every clause of it is a statement (or a greeting before one); referents are resolved
against the lexicon as the command grammar's are (one entity, a clarifying question when several
fit, "I don't know any..." when none does: nothing is invented). A liking's object may also be a
kind ("tea"): its words are passed on and found among the KB's classes when learnt. What only looks
like a statement is left to the other rules: a liking of what happens or of doing something ("I like
it when you dance", "I like to dance", "I like that"), and where the speaker is said of anything but
a zone or furniture the KB knows ("I'm on my way", "I'm on the phone").
"""

from __future__ import annotations

import re
from functools import cached_property

from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.resolution import PLACE
from dialogue.schema import FactClaim
from dialogue.understanding.language import Language
from dialogue.understanding.replies import say
from dialogue.understanding.said import Said, Text
from dialogue.understanding.speech.clauses import clauses as run_on_clauses
from dialogue.understanding.speech.plain import original_text
from dialogue.understanding.speech.repair import asked_verb, normalise
from dialogue.understanding.statements.clause import Refused, Told, Unclaimed, Words, fact
from dialogue.understanding.statements.likings import Likings
from dialogue.understanding.statements.names import clean_name, given_name, name_like
from dialogue.understanding.tables.prefixes import Prefixes

__all__ = ["Statements", "Told", "Words"]

ME = "me"
_HOLDERS: frozenset[Kind] = frozenset({"thing", "person"})
_THING: frozenset[Kind] = frozenset({"thing"})
#: What a person may be in or on: a zone, or furniture (not "on the phone").
_FURNITURE = "cyc:FurniturePiece"
class _Words:
    """The language's words of statements (`statements.toml`; made once per language)."""

    def __init__(self, lang: Language) -> None:
        said = lang.statements
        self.clauses = said.clauses
        self.leads = said.leads
        self.by_the_way = said.by_the_way
        #: A clause starting with one of these asks something: questions are not statements.
        self.asking = said.asking
        self.relatives = said.relatives
        self.friends = said.friends
        self.put = said.put
        #: Locative prepositions, longest first, and the property each states.
        self.states = lang.prepositions.phrase_column("states")
        self.be = said.be
        self.polite = said.polite
        self.no = said.no
        self.name_asked = said.name_asked
        #: What introduces the speaker's name, and whether it says a name surely ("my name is frank")
        #: or only when the words look like one ("call me later" is no name).
        self.name_leads = (*((lead, True) for lead in said.name_leads_surely),
                           *((lead, False) for lead in said.name_leads))  # fmt: skip
        #: "this is my phone", "these are my keys": what the speaker points at is theirs.
        self.pointed = said.pointed
        #: Greetings said before more words in the same clause, longest first ("hi there my name
        #: is..."); "morning", "evening" and "welcome" may be what a statement is about.
        self.greetings = Prefixes(lang.social.greetings_longest_first)
        self.openings = Prefixes(g for g in self.greetings if g not in said.greeting_topics)
        #: Words said last that are not part of the statement ("..., please").
        self.trailing = said.trailing
        #: "Bob is my name", "I am Bob", "his name is Rob", "it is Rob", "this is Maria".
        self.name_last, self.i_am, self.it_is = said.name_last, said.i_am, said.it_is
        self.their_name, self.name_is = said.their_name, said.name_is
        self.introducing = said.introducing
        #: "the bike belongs to me", "I own the bike".
        self.belongs_to, self.to_me, self.i_own = said.belongs_to, said.to_me, said.i_own
        #: Words between the verb and the place that say when ("the keys are usually in the drawer").
        self.when = said.when
        #: What an introduction may say besides the name ("I'm Priya, Sam's mum"), not learnt.
        self.remark_subjects, self.remark_verbs = said.remark_subjects, said.remark_verbs
        self.apposed = said.apposed
        self.remark_denials, self.remark_of = said.remark_denials, said.remark_of
        self.owner_ending = said.owner_ending


def _starts(words: Words, lead: Words) -> bool:
    """Whether the words start with the phrase (never with a phrase the language leaves empty)."""
    return bool(lead) and words[: len(lead)] == lead


def _holds_people(entity: Entity) -> bool:
    return entity.kind == "zone" or _FURNITURE in entity.classes


def _after_greeting(lang: Language, words: Words) -> Words | None:
    """The words after a greeting that opens them, when more follows it."""
    openings = lang.derived(_Words).openings
    found = next((g for g in openings.of(words) if len(words) > len(g)), None)
    return words[len(found) :] if found is not None else None


class Statements(Likings):
    """Reads statements against a lexicon, for one speaker and the dialogue's history."""

    @cached_property
    def said(self) -> _Words:
        """The language's words of statements (asked ~18 times a turn: looked up once per reader)."""
        return self.lang.derived(_Words)


    def read(self, text: Text) -> Told | None:
        """The facts of a turn of statements, or None when the turn is not one."""
        said = Said.read(self.lang, text)
        if said.text.rstrip().endswith("?"):
            return None  # a question (dialogue.understanding.questions.told reads those about what was told)
        told = Told()
        # run-on clauses too: "my keys are in the drawer can you get them" is no statement only
        clauses = [part for c in self.said.clauses.split(said.text) if c.strip()
                   for part in run_on_clauses(self.lang, said.of(c))]  # fmt: skip
        correcting = False
        refused: Refused | None = None  # said once every clause is known to be a statement
        try:
            for clause in clauses:
                words = self._lead(normalise(self.lang, said.of(clause)))
                if not words:
                    continue
                if self._greeting(words):
                    told.greeted = True
                    continue
                after = _after_greeting(self.lang, words)
                if after is not None:  # "hiya my name is Frank" ("hiya what's on the desk" asks)
                    told.greeted, words = True, self._lead(list(after))
                    if not words:
                        continue
                if words in self.said.polite:
                    continue
                if words in self.said.no:  # "no, it's Rob": what follows corrects the robot
                    correcting = True
                    continue
                try:
                    told.facts += self._statement(words, said.of(clause), correcting)
                except Refused as refusal:
                    refused = refused or refusal
                except Unclaimed:
                    if not self._remark(words, told):
                        raise
        except Unclaimed:
            return None
        if refused is not None:
            return Told(reply=refused.reply, clarify=refused.clarify)
        return told if told.facts else None

    def _remark(self, w: Words, told: Told) -> bool:
        """Whether a clause that is no statement of its own says what an introduction in the same
        turn may say besides the name ("I'm Priya, *Sam's mum*", "this is Ben, *he's visiting*"):
        the KB has no property for it, so it is heard and not learnt."""
        if not any(f.predicate == "name" for f in told.facts):
            return False
        said = self.said
        owner = said.owner_ending
        if len(w) > 2 and w[0] in said.remark_subjects and w[1] in said.remark_verbs:
            w = w[2:]
            if w[:1] and w[0] not in said.apposed and not (owner and w[0].endswith(owner)):
                return w[0] not in said.remark_denials  # ("he's visiting", not "he's not Ben")
        elif _starts(w, said.i_am):  # ("I'm Priya, I'm Sam's mum": only who the speaker is to someone)
            w = w[len(said.i_am) :]
        w = w[1:] if w[:1] and (w[0] in said.apposed or (owner and w[0].endswith(owner))) else w
        to = next((i for i, word in enumerate(w) if word in said.remark_of), len(w))
        related = w[:to]
        return len(related) == 1 and related[0] in said.friends

    def _lead(self, words: list[str]) -> Words:
        while words and (words[0] in self.said.leads or tuple(words[:3]) == self.said.by_the_way):
            words = words[3:] if tuple(words[:3]) == self.said.by_the_way else words[1:]
        while len(words) > 1 and words[-1] in self.said.trailing:
            words = words[:-1]
        return tuple(words)

    def _greeting(self, words: Words) -> bool:
        social = self.lang.social.social
        if words in social:
            return True
        return any(words[len(g) :] in social | {()} for g in self.said.greetings.of(words))

    # -- one clause ----------------------------------------------------------------------------
    def _statement(self, w: Words, clause: Said, correcting: bool = False) -> list[FactClaim]:
        """One clause's facts. After "no" ("no, it's Rob", "no, they're in the drawer") the name
        reader is told the robot is being corrected; the others read the clause as it is."""
        if w[0] in self.said.asking:
            raise Unclaimed
        verb = next((i for i, word in enumerate(w) if word in self.said.be), 0)
        if verb > 1 and w[verb - 1] in self.said.relatives:  # ("the one that's mine": no statement)
            raise Unclaimed
        named = ("no", *w) if correcting else w
        readers = ((self._name, named), (self._preference, w), (self._ownership, w), (self._location, w))
        for reader, words in readers:
            facts = reader(words, clause)
            if facts is not None:
                return facts
        raise Unclaimed

    def _name(self, w: Words, clause: Said) -> list[FactClaim] | None:
        correcting = w[:1] == ("no",)
        if correcting:
            w = self._lead(list(w[1:]))
        for lead, surely in self.said.name_leads:
            rest = w[len(lead) :]
            if w[: len(lead)] == lead and rest:
                if not (given_name(self.lang, rest) if surely else self._name_like(rest, clause)):
                    raise Unclaimed  # "my name is not important", "call me later"
                return [self._named(self.speaker, rest, clause)]
        said = self.said
        last = len(said.name_last)
        if last and w[-last:] == said.name_last and given_name(self.lang, w[:-last]):  # "Bob is my name"
            return [self._named(self.speaker, w[:-last], clause)]
        if _starts(w, said.i_am) and self._name_like(w[len(said.i_am) :], clause):
            return [self._named(self.speaker, w[len(said.i_am) :], clause)]
        if w[:2] in said.their_name and w[2:3] and w[2] in said.name_is:
            return [self._named(self._stranger(), w[3:], clause)]
        introducing = next((lead for lead in said.introducing if _starts(w, lead)), None)
        if introducing is not None:
            rest = w[len(introducing) :]
            if rest[:1] == ("my",) and rest[1:2] and rest[1] in self.said.friends:
                rest = rest[2:]
            if self._name_like(rest, clause) and not self._known_words(rest):
                who = self.speaker if self._asked_name() else self._stranger()
                return [self._named(who, rest, clause)]
            return None
        answer = w[len(said.it_is) :] if _starts(w, said.it_is) else w
        if (correcting or self._asked_name()) and self._name_like(answer, clause):
            who = self._last_named() if correcting else self.speaker
            return [self._named(who, answer, clause)]
        return None

    def _name_like(self, words: Words, clause: Said) -> bool:
        return name_like(self.lang, words, clause.of(original_text(self.lang, clause, list(words))))

    def _named(self, who: str, words: Words, clause: Said) -> FactClaim:
        name = clean_name(clause.of(original_text(self.lang, clause, list(words))))
        if not name:
            raise Unclaimed  # longer than any name
        return fact(who, "name", name)

    def _known_words(self, words: Words) -> bool:
        return all(self.lexicon.knows(w) for w in words)

    def _stranger(self) -> str:
        """ "this is Maria": the one person present whose name the robot does not know."""
        unnamed = [e for e in self.snapshot.visible()
                   if e.kind == "person" and e.id != self.speaker and not e.labels]  # fmt: skip
        if len(unnamed) == 1:
            return unnamed[0].id
        if not unnamed:
            raise Refused(say(self.lang, "sorry.no_one_unnamed"))
        raise Refused(say(self.lang, "sorry.several_unnamed"))

    def _robot_said(self) -> str:
        said = [u for u in self.history if u.role == "assistant"]
        return said[-1].text if said else ""

    def _asked_name(self) -> bool:
        last = self._robot_said().lower()
        return last.rstrip().endswith("?") and any(p in last for p in self.said.name_asked)

    def _last_named(self) -> str:
        """Whose name the robot's last reply said: "no, it's Rob" corrects it (the speaker first)."""
        said = self._robot_said()
        for entity in (self.snapshot.get(self.speaker), *self.snapshot.visible()):
            if entity is not None and entity.kind == "person" and any(
                re.search(rf"\b{re.escape(label)}\b", said) for label in entity.labels
            ):
                return entity.id
        raise Unclaimed




    def _ownership(self, w: Words, clause: Said) -> list[FactClaim] | None:
        if len(w) > 2 and w[-1] == "mine" and w[-2] in self.said.be:
            thing, _ = self._entity(w[:-2], _THING)
            return [fact(thing, "belongsTo", self.speaker)]
        for verb in self.said.belongs_to:
            n = len(verb)
            for i in range(1, len(w) - n):
                if w[i : i + n] == verb:
                    whom = w[i + n :]
                    owner = ME if len(whom) == 1 and whom[0] in self.said.to_me else self._person(whom)
                    if owner is None:
                        called = " ".join(whom).title()
                        raise Refused(say(self.lang, "sorry.no_one_called", name=called))
                    thing, _ = self._entity(w[:i], _THING)
                    return [fact(thing, "belongsTo", self.speaker if owner == ME else owner)]
        if w[:2] in self.said.pointed and w[2:3] == ("my",) and w[3:]:
            thing, _ = self._entity(w[3:], _THING)
            return [fact(thing, "belongsTo", self.speaker)]
        if len(w) > 2 and w[-2] in self.said.be and w[-1].endswith("'s"):
            owner = self._person((w[-1][:-2],))
            if owner is not None:
                thing, _ = self._entity(w[:-2], _THING)
                return [fact(thing, "belongsTo", owner)]
        if _starts(w, self.said.i_own) and w[len(self.said.i_own) :]:
            thing, _ = self._entity(w[len(self.said.i_own) :], _THING)
            return [fact(thing, "belongsTo", self.speaker)]
        return None

    def _location(self, w: Words, clause: Said) -> list[FactClaim] | None:
        if _starts(w, self.said.i_am):
            return self._where(("me",), w[len(self.said.i_am) :], people_in=True)
        if w[:1] == ("i",) and len(w) > 3:
            verb = 2 if w[1] == "have" else 1
            return self._placed(w[verb + 1 :]) if w[verb] in self.said.put else None
        for i in range(1, len(w) - 1):
            if w[i] in self.said.be:
                if i > 1 and w[0] == asked_verb(self.lang, w[0]):
                    return None  # a request ("tell Ana her taxi is on time"), not a subject ("water is...")
                # "(no,) they're in the drawer": the subject pronoun as the thing it stands for
                subject = (self.lang.words.objects.get(w[0], w[0]),) if i == 1 else w[:i]
                return self._where(subject, w[i + 1 :])
        return None

    def _where(self, thing: Words, rest: Words, people_in: bool = False) -> list[FactClaim] | None:
        """ "(the keys are) in the drawer": the place after the verb. With `people_in` ("I'm in
        the kitchen", "I'm on the sofa") only a zone or furniture the KB knows is a place; other
        words are an idiom ("I'm on my way", "I'm in trouble", "I'm on the phone")."""
        rest = rest[1:] if rest[:1] and rest[0] in self.said.when else rest
        while rest[-1:] and rest[-1] in self.said.when:  # ("it's on the shelf now")
            rest = rest[:-1]
        for prep, predicate in self.said.states.items():
            place = rest[len(prep) :]
            if rest[: len(prep)] == prep and place and people_in:
                here, _ = self._entity(place, PLACE, _holds_people)
                return [fact(self.speaker, predicate, here)]
            if rest[: len(prep)] == prep and place:
                return self._at(thing, predicate, place)
        return None

    def _placed(self, rest: Words) -> list[FactClaim] | None:
        for i in range(1, len(rest)):
            for prep, predicate in self.said.states.items():
                if rest[i : i + len(prep)] == prep and rest[i + len(prep) :]:
                    return self._at(rest[:i], predicate, rest[i + len(prep) :])
        return None

    def _at(self, thing_words: Words, predicate: str, place_words: Words) -> list[FactClaim]:
        thing, owner = self._entity(thing_words, _HOLDERS)
        place, _ = self._entity(place_words, PLACE)
        facts = []
        entity = self.snapshot.get(thing)
        if owner is not None and entity is not None and entity.owner is None:
            facts.append(fact(thing, "belongsTo", owner))  # "my glasses": theirs, said in passing
        return [*facts, fact(thing, predicate, place)]

