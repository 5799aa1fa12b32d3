"""The rules' grammar of statements: what a person tells the robot, as facts of the answer schema.

    I'm Bob · my name is Bob · call me Bob · no, it's Rob      -> <speaker> name "Bob"
    this is Maria (exactly one person present has no name)    -> <that person> name "Maria"
    the red mug is mine · that phone belongs to Ines          -> <thing> belongsTo <person>
    the keys are in the drawer · I left my glasses on the sofa -> <thing> isIn / isOn <place>
    I like tea · Alice hates coffee · I don't like the radio  -> <person> likes / dislikes <kind or thing>

A turn is claimed only when every clause of it is a statement (or a greeting before one); referents
are resolved against the lexicon as the command grammar's are (one entity, a clarifying question when
several fit, "I don't know any..." when none does: nothing is invented). A liking's object may also
be a kind ("tea"): its words are passed on and found among the KB's classes when learnt.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from lemminflect import getAllLemmas

from dialogue.history import Utterance
from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.english import POSSESSIVES, word_set
from dialogue.reference.grounding import Kind
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import (
    ANYWHERE,
    PERSON,
    PLACE,
    antecedent,
    content_words,
    is_pronoun,
    resolve,
)  # fmt: skip
from dialogue.rules.clauses import clauses as run_on_clauses
from dialogue.rules.speech import original_text
from dialogue.rules.utterance import asked_verb, normalise
from dialogue.rules.words import GREETINGS, NEEDS, SOCIAL
from dialogue.schema import FactClaim

Words = tuple[str, ...]
ME = "me"
_HOLDERS: frozenset[Kind] = frozenset({"thing", "person"})
_THING: frozenset[Kind] = frozenset({"thing"})
_CLAUSES = re.compile(r"[.;!?,]+(?:\s+|$)|\s+(?=and\s+(?:i|my|the|this|that|he|she|it)\b)", re.I)
_LEADS = word_set("well oh so ok okay actually also and anyway listen hey robot")
_BY_THE_WAY = ("by", "the", "way")
#: A clause starting with one of these asks something: questions are not statements.
_ASKING = word_set("do does did is are was were can could would will shall should may might must have has")
_INTENSIFIERS = word_set("really truly absolutely quite totally just")
#: Words of "I'm X" that are no name ("I'm back", "I'm the cook", "I'm not sure").
_NOT_NAMES = word_set(
    "a an the not no so very just here there back home in on at from with going done fine ok okay sorry "
    "ready sure afraid looking trying still also only really quite too that this it what who your my"
)
_FRIEND = word_set(
    "friend wife husband partner son daughter mother mum mom father dad brother sister colleague boss "
    "neighbour neighbor guest grandmother grandfather granny grandma grandpa aunt uncle cousin"
)
_LIKE = word_set("like likes love loves enjoy enjoys adore adores")
_HATE = word_set("hate hates dislike dislikes detest detests loathe loathes")
_PUT = word_set("left put placed keep kept stored leave")
#: Locative prepositions, longest first, and the property each states.
_IN = {("on", "top", "of"): "isOn", ("in",): "isIn", ("inside",): "isIn", ("into",): "isIn", ("on",): "isOn",
       ("onto",): "isOn"}  # fmt: skip
_BE = word_set("is are")
_POLITE: frozenset[Words] = frozenset({("please",), ("thanks",), ("thank", "you"), ("ok",), ("okay",)})
_NO: frozenset[Words] = frozenset({("no",), ("nope",), ("no", "no"), ("wrong",), ("that", "is", "wrong"),
                                   ("not", "quite"), ("sorry",), ("no", "sorry")})
_NAME_ASKED = ("your name", "what should i call you")


@dataclass
class Told:
    """The rules' reading of a turn of statements: the facts, or the reply that says why none."""

    facts: list[FactClaim] = field(default_factory=list)
    reply: str | None = None
    clarify: bool = False
    greeted: bool = False


class _Unclaimed(Exception):
    """A clause is not a statement this grammar reads: the turn is left to the other rules."""


class _Refused(Exception):
    """A statement whose referent is unknown or ambiguous: the reply says so (no fact)."""

    def __init__(self, reply: str, clarify: bool = False) -> None:
        super().__init__(reply)
        self.reply = reply
        self.clarify = clarify


def _fact(subject: str, predicate: str, obj: str | None) -> FactClaim:
    return FactClaim(subject=subject, predicate=predicate, object=obj)


def name_like(words: Words, original: str) -> bool:
    """Whether the words of "I'm X" are a name: one to three words, none a function word, and
    (for lower-case speech-recogniser text) none an adjective or adverb ("I'm tired", "I'm here")."""
    # ("I'm peckish": a need the rules' grammar reads, whatever a lemmatiser knows of the word)
    if not 1 <= len(words) <= 3 or any(w in _NOT_NAMES or w in NEEDS or not w.isalpha() for w in words):
        return False
    if original != original.lower():  # written casing tells names apart: "I'm Frank", "I'm frank"
        return all(part[:1].isupper() for part in original.split())
    lemmas = [getAllLemmas(w) for w in words]
    return not any({"ADJ", "ADV", "AUX"} & set(found) for found in lemmas) and not words[0].endswith("ing")


class Statements:
    """Reads statements against a lexicon, for one speaker and the dialogue's history."""

    def __init__(self, lexicon: Lexicon, speaker: str, history: Sequence[Utterance] = (),
                 overrides: Mapping[Words, Words] | None = None) -> None:
        self.lexicon = lexicon
        self.snapshot = lexicon.snapshot
        self.speaker = speaker
        #: Phrases read as other words: an ambiguous one completed by the answer to the robot's
        #: question (dialogue.memory.followup).
        self.overrides = dict(overrides or {})
        #: The phrase the last clarifying question was about.
        self.open_phrase: Words | None = None
        self.history = tuple(history)

    def read(self, text: str) -> Told | None:
        """The facts of a turn of statements, or None when the turn is not one."""
        if text.rstrip().endswith("?"):
            return None  # a question (dialogue.memory.asking reads those about what was told)
        told = Told()
        # run-on clauses too: "my keys are in the drawer can you get them" is no statement only
        clauses = [part for c in _CLAUSES.split(text) if c.strip() for part in run_on_clauses(c)]
        correcting = False
        refused: _Refused | None = None  # said once every clause is known to be a statement
        try:
            for clause in clauses:
                words = self._lead(normalise(clause))
                if not words:
                    continue
                if self._greeting(words):
                    told.greeted = True
                    continue
                if words in _POLITE:
                    continue
                if words in _NO:  # "no, it's Rob": what follows corrects the robot
                    correcting = True
                    continue
                try:
                    told.facts += self._statement(("no", *words) if correcting else words, clause)
                except _Refused as refusal:
                    refused = refused or refusal
        except _Unclaimed:
            return None
        if refused is not None:
            return Told(reply=refused.reply, clarify=refused.clarify)
        return told if told.facts else None

    @staticmethod
    def _lead(words: list[str]) -> Words:
        while words and (words[0] in _LEADS or tuple(words[:3]) == _BY_THE_WAY):
            words = words[3:] if tuple(words[:3]) == _BY_THE_WAY else words[1:]
        while len(words) > 1 and words[-1] in {"please", "thanks"}:
            words = words[:-1]
        return tuple(words)

    @staticmethod
    def _greeting(words: Words) -> bool:
        if words in SOCIAL:
            return True
        return any(words[: len(g)] == g and words[len(g) :] in SOCIAL | {()} for g in GREETINGS)

    # -- one clause ----------------------------------------------------------------------------
    def _statement(self, w: Words, clause: str) -> list[FactClaim]:
        if w[0] in _ASKING or w[0] in {"what", "where", "who", "which", "whose", "how", "why", "when"}:
            raise _Unclaimed
        for reader in (self._name, self._preference, self._ownership, self._location):
            facts = reader(w, clause)
            if facts is not None:
                return facts
        raise _Unclaimed

    def _name(self, w: Words, clause: str) -> list[FactClaim] | None:
        correcting = w[:1] == ("no",)
        if correcting:
            w = self._lead(list(w[1:]))
        for lead in (("my", "name", "is"), ("my", "name's"), ("call", "me"), ("you", "can", "call", "me"),
                     ("i", "am", "called"), ("people", "call", "me"), ("the", "name", "is")):
            if w[: len(lead)] == lead and w[len(lead) :]:
                return [self._named(self.speaker, w[len(lead) :], clause)]
        if w[:2] == ("i", "am") and name_like(w[2:], original_text(clause, list(w[2:]))):
            return [self._named(self.speaker, w[2:], clause)]
        if w[:2] in {("his", "name"), ("her", "name"), ("their", "name")} and w[2:3] in {("is",), ("'s",)}:
            return [self._named(self._stranger(), w[3:], clause)]
        if w[:2] in {("this", "is"), ("here", "is"), ("meet",)} or w[:1] == ("meet",):
            rest = w[2:] if w[0] != "meet" else w[1:]
            if rest[:1] == ("my",) and rest[1:2] and rest[1] in _FRIEND:
                rest = rest[2:]
            if name_like(rest, original_text(clause, list(rest))) and not self._known_words(rest):
                who = self.speaker if self._asked_name() else self._stranger()
                return [self._named(who, rest, clause)]
            return None
        answer = w[2:] if w[:2] == ("it", "is") else w
        if (correcting or self._asked_name()) and name_like(answer, original_text(clause, list(answer))):
            who = self._last_named() if correcting else self.speaker
            return [self._named(who, answer, clause)]
        return None

    def _named(self, who: str, words: Words, clause: str) -> FactClaim:
        name = original_text(clause, list(words))
        return _fact(who, "name", name if name != name.lower() else name.title())

    def _known_words(self, words: Words) -> bool:
        return all(self.lexicon.knows(w) for w in words)

    def _stranger(self) -> str:
        """ "this is Maria": the one person present whose name the robot does not know."""
        unnamed = [e for e in self.snapshot.visible()
                   if e.kind == "person" and e.id != self.speaker and not e.labels]  # fmt: skip
        if len(unnamed) == 1:
            return unnamed[0].id
        if not unnamed:
            raise _Refused("Sorry, I don't see anyone here whose name I don't know.")
        raise _Refused("Sorry, I see more than one person I don't know: I can't tell who you mean.")

    def _robot_said(self) -> str:
        said = [u for u in self.history if u.role == "assistant"]
        return said[-1].text if said else ""

    def _asked_name(self) -> bool:
        last = self._robot_said().lower()
        return last.rstrip().endswith("?") and any(p in last for p in _NAME_ASKED)

    def _last_named(self) -> str:
        """Whose name the robot's last reply said: "no, it's Rob" corrects it (the speaker first)."""
        said = self._robot_said()
        for entity in (self.snapshot.get(self.speaker), *self.snapshot.visible()):
            if entity is not None and entity.kind == "person" and any(
                re.search(rf"\b{re.escape(label)}\b", said) for label in entity.labels
            ):
                return entity.id
        raise _Unclaimed

    def _preference(self, w: Words, clause: str) -> list[FactClaim] | None:
        w = tuple(x for x in w if x not in _INTENSIFIERS)
        if w[:3] == ("i", "cannot", "stand") and w[3:]:
            return [_fact(self.speaker, "dislikes", self._liked(w[3:]))]
        for cut in range(1, min(len(w) - 1, 4)):  # the subject: one to three words
            verb, negated = cut, False
            if w[cut : cut + 2] in {("do", "not"), ("does", "not")}:
                verb, negated = cut + 2, True
            elif w[cut] == "don't":
                verb, negated = cut + 1, True
            if verb + 1 >= len(w):
                continue
            if w[verb] in _LIKE:
                predicate = "dislikes" if negated else "likes"
            elif w[verb] in _HATE and not negated:
                predicate = "dislikes"
            else:
                continue
            who = self._person(w[:cut])
            if who is not None:
                return [_fact(who, predicate, self._liked(w[verb + 1 :]))]
        return None

    def _person(self, words: Words) -> str | None:
        if words == ("i",):
            return self.speaker
        if words in {("he",), ("she",)}:
            found = antecedent(self.lexicon, self.history, PERSON, speaker=self.speaker)
            return found.id if found is not None else None
        if not content_words(words) or not all(w.isalpha() for w in words):
            return None
        res = resolve(self.lexicon, words, PERSON)
        if res.ambiguous:
            raise _Refused(clarifying_question(self.snapshot, res.matches), clarify=True)
        return res.one.id if res.one is not None else None

    def _liked(self, words: Words) -> str:
        """A thing of the situation when the phrase names one with a determiner ("the radio"), else
        the words of a kind ("tea", "apples"), found among the KB's classes when learnt."""
        words = tuple(w for w in words if w not in {"very", "much", "really", "so", "a", "lot", "too"})
        if words and words[0].endswith("ing") and "VERB" in getAllLemmas(words[0]):
            raise _Unclaimed  # "I hate marking lab reports": an activity, no thing or kind of the KB
        if words and words[0] in {"the", "this", "that", "my", "your", "his", "her"}:
            return self._entity(words, ANYWHERE)[0]
        if words == ("you",):
            return self.snapshot.robot
        person = self._person(words) if words[:1] != ("it",) else None
        if person is not None:
            return person
        return " ".join(words)

    def _ownership(self, w: Words, clause: str) -> list[FactClaim] | None:
        if len(w) > 2 and w[-1] == "mine" and w[-2] in _BE:
            thing, _ = self._entity(w[:-2], _THING)
            return [_fact(thing, "belongsTo", self.speaker)]
        for verb in (("belongs", "to"), ("belong", "to")):
            for i in range(1, len(w) - 2):
                if w[i : i + 2] == verb:
                    owner = ME if w[i + 2 :] in {("me",), ("myself",)} else self._person(w[i + 2 :])
                    if owner is None:
                        raise _Refused(f"Sorry, I don't know anyone called {' '.join(w[i + 2:]).title()}.")
                    thing, _ = self._entity(w[:i], _THING)
                    return [_fact(thing, "belongsTo", self.speaker if owner == ME else owner)]
        if w[:2] in {("this", "is"), ("that", "is"), ("it", "is")} and w[2:3] == ("my",) and w[3:]:
            thing, _ = self._entity(w[3:], _THING)
            return [_fact(thing, "belongsTo", self.speaker)]
        if len(w) > 2 and w[-2] in _BE and w[-1].endswith("'s"):
            owner = self._person((w[-1][:-2],))
            if owner is not None:
                thing, _ = self._entity(w[:-2], _THING)
                return [_fact(thing, "belongsTo", owner)]
        if w[:2] == ("i", "own") and w[2:]:
            thing, _ = self._entity(w[2:], _THING)
            return [_fact(thing, "belongsTo", self.speaker)]
        return None

    def _location(self, w: Words, clause: str) -> list[FactClaim] | None:
        if w[:2] == ("i", "am"):
            return self._where(("me",), w[2:])
        if w[:1] == ("i",) and len(w) > 3:
            verb = 2 if w[1] == "have" else 1
            return self._placed(w[verb + 1 :]) if w[verb] in _PUT else None
        for i in range(1, len(w) - 1):
            if w[i] in _BE:
                if i > 1 and w[0] == asked_verb(w[0]):
                    return None  # a request ("tell Ana her taxi is on time"), not a subject ("water is...")
                return self._where(w[:i], w[i + 1 :])
        return None

    def _where(self, thing: Words, rest: Words) -> list[FactClaim] | None:
        """ "(the keys are) in the drawer": the place after the verb."""
        rest = rest[1:] if rest[:1] in {("now",), ("still",), ("usually",), ("always",)} else rest
        for prep, predicate in _IN.items():
            if rest[: len(prep)] == prep and rest[len(prep) :]:
                return self._at(thing, predicate, rest[len(prep) :])
        return None

    def _placed(self, rest: Words) -> list[FactClaim] | None:
        for i in range(1, len(rest)):
            for prep, predicate in _IN.items():
                if rest[i : i + len(prep)] == prep and rest[i + len(prep) :]:
                    return self._at(rest[:i], predicate, rest[i + len(prep) :])
        return None

    def _at(self, thing_words: Words, predicate: str, place_words: Words) -> list[FactClaim]:
        thing, owner = self._entity(thing_words, _HOLDERS)
        place, _ = self._entity(place_words, PLACE)
        facts = []
        entity = self.snapshot.get(thing)
        if owner is not None and entity is not None and entity.owner is None:
            facts.append(_fact(thing, "belongsTo", owner))  # "my glasses": theirs, said in passing
        return [*facts, _fact(thing, predicate, place)]

    def _entity(self, words: Words, kinds: frozenset[Kind]) -> tuple[str, str | None]:
        """One entity of `kinds` the phrase names, and whose it is said to be ("my keys")."""
        self.open_phrase, words = words, self.overrides.get(words, words)
        if "person" in kinds and words in {("me",), ("i",)}:
            return self.speaker, None
        said = [w for w in words if w in POSSESSIVES]
        owner = self.speaker if said[:1] in (["my"], ["our"]) else None
        bare = tuple(w for w in words if w not in POSSESSIVES)
        if not content_words(bare) or is_pronoun(bare):
            found = antecedent(self.lexicon, self.history, kinds, speaker=self.speaker)
            if found is None:
                raise _Refused(f'What do you mean by "{" ".join(words)}"?', clarify=True)
            return found.id, owner
        res = resolve(self.lexicon, bare, kinds, owner=owner)
        if res.one is not None:
            return res.one.id, owner
        if res.ambiguous:
            raise _Refused(clarifying_question(self.snapshot, res.matches), clarify=True)
        if any(not self.lexicon.knows(w) for w in content_words(bare)) and any(
            self.lexicon.knows(w) for w in content_words(bare)
        ):
            raise _Unclaimed  # names the KB knows among words it does not: leave it to a model
        raise _Refused(f"Sorry, I don't know any {' '.join(content_words(bare))}.")
