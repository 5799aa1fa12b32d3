"""What the robot says back about what it was told or asked: one sentence per claim.

"Nice to meet you, Bob." · "OK, the red mug is yours." · "I can see the keys on the table, though."
· "OK, I'll remember that you said the phone belongs to Ines." · "Alice likes tea."
"""

from __future__ import annotations

from dialogue.memory.claims import Claim
from dialogue.memory.learn import Outcome, Settled
from dialogue.reference.grounding import Entity, Snapshot
from dialogue.understanding.inflection import plural_name
from dialogue.understanding.language import Language
from dialogue.understanding.replies import capitalised, listing, the
from dialogue.understanding.replies import say as _say


class _Namer:
    """Names for a turn's sentences (said in the language's words: its `replies.toml` [learnt]):
    entities as the rules name them, kinds and names as told."""

    def __init__(self, lang: Language, snapshot: Snapshot, speaker: str, names: dict[str, str]) -> None:
        self.lang = lang
        self.snapshot = snapshot
        self.speaker = speaker
        self.names = names
        #: The preposition each property a place is told with is said with ("isIn": "in").
        self.prepositions = {state: p for p, state in lang.prepositions.column("says").items()}
        self.you = self.say("naming.you")

    def say(self, key: str, **slots: object) -> str:
        return _say(self.lang, key, **slots)

    def __call__(self, term: str) -> str:
        if term == self.snapshot.robot:
            return self.say("naming.me")  # "OK, you like me."
        entity = self.snapshot.get(term)
        if entity is None:
            return self.names.get(term) or self.snapshot.name_of(term)
        named = the(self.lang, self.snapshot, entity, self.speaker)
        if entity.colour and entity.colour not in named and self._shared(entity.id, named):
            # "the red mug", of two mugs
            coloured = self.say("naming.the_coloured", colour=entity.colour, name="")
            return named.replace(self.say("naming.the", name=""), coloured, 1)
        return named

    def _shared(self, term: str, named: str) -> bool:
        """Whether another thing of the situation goes by the same name."""
        return any(e.id != term and e.kind == "thing" and self._the(e) == named
                   for e in self.snapshot.visible())  # fmt: skip

    def _the(self, entity: Entity) -> str:
        return the(self.lang, self.snapshot, entity, self.speaker)

    def person(self, term: str, fallback: str | None = None) -> str:
        if term == self.speaker:
            return self.you
        entity = self.snapshot.get(term)
        if entity is not None and entity.labels:
            return entity.name
        return fallback if fallback is not None else self.say("learnt.they")

    def owner(self, term: str) -> str:
        if term == self.speaker:
            return self.say("learnt.yours")
        return self.say("learnt.owners", who=self.person(term, self.say("learnt.someone_else")))

    def be(self, name: str) -> str:
        # (number by the head noun's English, not its spelling: "Ines is", "the keys are")
        return self.say("learnt.are" if name == self.you or plural_name(name, self.lang) else "learnt.is")

    def at(self, prop: str) -> str:
        return self.prepositions.get(prop) or self.say("learnt.at")


def clause(claim: Claim, name: _Namer, obj: str | None = None) -> str:
    """A statement as a clause: "the phone belongs to Ines", "you like tea", "your name is Bob"."""
    value = obj if obj is not None else (claim.object or "")
    who = name.person(claim.subject, name(claim.subject))
    match claim.predicate:
        case "name":
            if claim.subject == name.speaker:
                return name.say("learnt.your_name", value=value)
            return name.say("learnt.name_of", who=who, value=value)
        case "belongsTo":
            thing = name(claim.subject)
            return name.say("learnt.belongs", thing=thing, be=name.be(thing), owner=name.owner(value))
        case "isIn" | "isOn":
            thing = name(claim.subject)
            return name.say("learnt.placed", thing=thing, be=name.be(thing),
                            preposition=name.at(claim.predicate), place=name(value))  # fmt: skip
        case "likes":
            key = "learnt.you_like" if who == name.you else "learnt.likes"
            return name.say(key, who=who, value=name(value))
        case _:
            key = "learnt.you_dislike" if who == name.you else "learnt.dislikes"
            return name.say(key, who=who, value=name(value))


#: What each status of a claim that is no name says, around the claim as a clause.
_SAID_OF = {"adopted": "learnt.adopted", "known": "learnt.known", "believed": "learnt.believed"}


def sentence(outcome: Outcome, name: _Namer) -> str:
    claim = outcome.claim
    match outcome.status:
        case "adopted" | "known" if claim.predicate == "name":
            return _named(outcome, name)
        case "adopted" | "known" | "believed":
            return name.say(_SAID_OF[outcome.status], clause=clause(claim, name, outcome.object))
        case "perceived":
            return _perceived(outcome, name)
        case "disputed":
            return _disputed(outcome, name)
        case "unknown":
            return name.say("learnt.unknown_kind", kind=outcome.object, be=name.be(outcome.object or ""))
        case _:
            return _answer(outcome, name)


def _named(outcome: Outcome, name: _Namer) -> str:
    told = outcome.object or ""
    if outcome.replaced:
        return name.say("learnt.renamed", name=told, before=listing(name.lang, list(outcome.replaced)))
    if outcome.status == "known":
        yours = outcome.claim.subject == name.speaker
        return name.say("learnt.known_yours" if yours else "learnt.known_theirs", name=told)
    return name.say("learnt.nice_to_meet", name=told)


def _perceived(outcome: Outcome, name: _Namer) -> str:
    claim = outcome.claim
    held = outcome.held
    if claim.predicate == "name":
        yours = claim.subject == name.speaker
        return name.say("learnt.known_as_you" if yours else "learnt.known_as_them",
                        names=listing(name.lang, [v for _, v in held]))  # fmt: skip
    if claim.predicate in name.prepositions:
        thing = name(claim.subject)
        places = listing(name.lang, [f"{name.at(p)} {name(v)}" for p, v in held])
        entity = name.snapshot.get(claim.subject)
        if entity is not None and entity.seen:
            return name.say("learnt.seen_at", thing=thing, places=places)
        return name.say("learnt.far_as_i_know_at", thing=thing, be=name.be(thing), places=places)
    facts = [clause(Claim(claim.subject, _predicate(p), v), name) for p, v in held]
    return name.say("learnt.far_as_i_know", facts=listing(name.lang, facts))


def _disputed(outcome: Outcome, name: _Namer) -> str:
    """Whose word holds: "I know someone else called Alice.", "Ana told me the mug is theirs."."""
    claim = outcome.claim
    (by, value), = outcome.hearsay
    if claim.predicate == "name":
        return name.say("learnt.someone_else_called", name=value)
    thing = name(claim.subject)
    owner = name.say("learnt.theirs") if by == value else name.owner(value)
    who = name.person(by, name.say("learnt.someone"))
    return capitalised(name.say("learnt.told_me_owned", who=who, thing=thing, be=name.be(thing), owner=owner))


def _predicate(prop: str) -> str:
    return {"rdfs:label": "name"}.get(prop, prop)


def _answer(outcome: Outcome, name: _Namer) -> str:
    claim = outcome.claim
    values = [v for _, v in outcome.held]
    if values and claim.predicate == "name" and claim.subject != name.speaker:
        return name.say("learnt.that_is", names=listing(name.lang, values))  # "what is her name?"
    if values:
        facts = [clause(Claim(claim.subject, claim.predicate, v), name) for v in values]
        if claim.predicate in {"likes", "dislikes"} and len(values) > 1:
            return capitalised(f"{clause(claim, name, listing(name.lang, [name(v) for v in values]))}.")
        return capitalised(f"{listing(name.lang, facts)}.")
    if outcome.hearsay:
        said = [name.say("learnt.told_me", who=name.person(who, name.say("learnt.someone")),
                         clause=clause(claim, name, v)) for who, v in outcome.hearsay[:3]]  # fmt: skip
        return capitalised(f"{listing(name.lang, said)}.")
    return _unknown_answer(claim, name)


def _unknown_answer(claim: Claim, name: _Namer) -> str:
    who = name.person(claim.subject, name(claim.subject))
    yours = who == name.you
    match claim.predicate:
        case "name" if claim.subject == name.speaker:
            return name.say("learnt.name_unknown_yours")
        case "name":
            whose = name.person(claim.subject, "")
            if not whose:
                return name.say("learnt.name_unknown_theirs")
            return name.say("learnt.name_unknown", whose=whose)
        case "belongsTo":
            thing = name(claim.subject).removeprefix(name.say("naming.the", name=""))
            return name.say("learnt.owner_unknown", thing=thing)
        case "isIn" | "isOn":
            thing = name(claim.subject)
            return name.say("learnt.place_unknown", thing=thing, be=name.be(thing))
        case "likes":
            return name.say("learnt.likes_unknown_yours" if yours else "learnt.likes_unknown", who=who)
        case _:
            return name.say("learnt.dislikes_unknown_yours" if yours else "learnt.dislikes_unknown", who=who)


def confirmation(lang: Language, settled: Settled, snapshot: Snapshot, speaker: str) -> str:
    """The reply to a turn's claims, one sentence each, in order, without repeats."""
    name = _Namer(lang, snapshot, speaker, settled.names)
    ok, also = name.say("learnt.ok"), name.say("learnt.and")
    sentences: list[str] = []
    for said in dict.fromkeys(sentence(o, name) for o in settled.outcomes):
        if sentences and sentences[-1].startswith(ok) and said.startswith(ok):  # "OK, a and b."
            sentences[-1] = f"{sentences[-1][:-1]}{also}{said[len(ok):]}"
        else:
            sentences.append(said)
    return " ".join(sentences)
