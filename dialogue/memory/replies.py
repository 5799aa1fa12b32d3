"""What the robot says back about what it was told or asked: one sentence per claim.

"Nice to meet you, Bob." · "OK, the red mug is yours." · "I can see the keys on the table, though."
· "OK, I'll remember that you said the phone belongs to Ines." · "Alice likes tea."
"""

from __future__ import annotations

from dialogue.memory.claims import Claim
from dialogue.memory.learn import Outcome, Settled
from dialogue.reference.english import tokens
from dialogue.reference.grounding import Snapshot
from dialogue.reference.lexicon import singular
from dialogue.understanding.questions.answers import listing, the

_PREPOSITION = {"isIn": "in", "isOn": "on"}
_OK = "OK, "


class _Namer:
    """Names for a turn's sentences: entities as the rules name them, kinds and names as told."""

    def __init__(self, snapshot: Snapshot, speaker: str, names: dict[str, str]) -> None:
        self.snapshot = snapshot
        self.speaker = speaker
        self.names = names

    def __call__(self, term: str) -> str:
        if term == self.snapshot.robot:
            return "me"  # "OK, you like me."
        entity = self.snapshot.get(term)
        if entity is None:
            return self.names.get(term) or self.snapshot.name_of(term)
        named = the(self.snapshot, entity, self.speaker)
        if entity.colour and entity.colour not in named and self._shared(entity.id, named):
            return named.replace("the ", f"the {entity.colour} ", 1)  # "the red mug", of two mugs
        return named

    def _shared(self, term: str, named: str) -> bool:
        """Whether another thing of the situation goes by the same name."""
        return any(e.id != term and e.kind == "thing" and the(self.snapshot, e, self.speaker) == named
                   for e in self.snapshot.visible())

    def person(self, term: str, fallback: str = "they") -> str:
        if term == self.speaker:
            return "you"
        entity = self.snapshot.get(term)
        return entity.name if entity is not None and entity.labels else fallback

    def owner(self, term: str) -> str:
        return "yours" if term == self.speaker else f"{self.person(term, 'someone else')}'s"


def _be(name: str) -> str:
    words = tokens(name)
    plural = bool(words) and singular(words[-1]) != words[-1] and name != "you"
    return "are" if plural or name == "you" else "is"


def _cap(sentence: str) -> str:
    return sentence[:1].upper() + sentence[1:]


def clause(claim: Claim, name: _Namer, obj: str | None = None) -> str:
    """A statement as a clause: "the phone belongs to Ines", "you like tea", "your name is Bob"."""
    value = obj if obj is not None else (claim.object or "")
    who = name.person(claim.subject, name(claim.subject))
    match claim.predicate:
        case "name":
            return f"your name is {value}" if claim.subject == name.speaker else f"{who}'s name is {value}"
        case "belongsTo":
            return f"{name(claim.subject)} {_be(name(claim.subject))} {name.owner(value)}"
        case "isIn" | "isOn":
            thing = name(claim.subject)
            return f"{thing} {_be(thing)} {_PREPOSITION[claim.predicate]} {name(value)}"
        case "likes":
            return f"{who} {'like' if who == 'you' else 'likes'} {name(value)}"
        case _:
            return f"{who} {'don' if who == 'you' else 'doesn'}'t like {name(value)}"


def sentence(outcome: Outcome, name: _Namer) -> str:
    claim = outcome.claim
    match outcome.status:
        case "adopted" | "known" if claim.predicate == "name":
            return _named(outcome, name)
        case "adopted":
            return f"OK, {clause(claim, name, outcome.object)}."
        case "known":
            return f"I know, {clause(claim, name, outcome.object)}."
        case "believed":
            return f"OK, I'll remember that you said {clause(claim, name, outcome.object)}."
        case "perceived":
            return _perceived(outcome, name)
        case "disputed":
            return _disputed(outcome, name)
        case "unknown":
            return f"Sorry, I don't know what {outcome.object} {_be(outcome.object or '')}."
        case _:
            return _answer(outcome, name)


def _named(outcome: Outcome, name: _Namer) -> str:
    told = outcome.object or ""
    if outcome.replaced:
        return f"Got it: {told}, not {listing(list(outcome.replaced))}."
    if outcome.status == "known":
        return f"I know, {told}." if outcome.claim.subject == name.speaker else f"Yes, that's {told}."
    return f"Nice to meet you, {told}."


def _perceived(outcome: Outcome, name: _Namer) -> str:
    claim = outcome.claim
    held = outcome.held
    if claim.predicate == "name":
        whom = "you" if claim.subject == name.speaker else "them"
        return f"I know {whom} as {listing([v for _, v in held])}, though."
    if claim.predicate in _PREPOSITION:
        thing = name(claim.subject)
        places = listing([f"{_PREPOSITION.get(p, 'at')} {name(v)}" for p, v in held])
        entity = name.snapshot.get(claim.subject)
        if entity is not None and entity.seen:
            return f"I can see {thing} {places}, though."
        return f"As far as I know, {thing} {_be(thing)} {places}."
    facts = [clause(Claim(claim.subject, _predicate(p), v), name) for p, v in held]
    return f"As far as I know, {listing(facts)}."


def _disputed(outcome: Outcome, name: _Namer) -> str:
    """Whose word holds: "I know someone else called Alice.", "Ana told me the mug is theirs."."""
    claim = outcome.claim
    (by, value), = outcome.hearsay
    if claim.predicate == "name":
        return f"I know someone else called {value}."
    thing = name(claim.subject)
    owner = "theirs" if by == value else name.owner(value)
    return f"{_cap(name.person(by, 'someone'))} told me {thing} {_be(thing)} {owner}."


def _predicate(prop: str) -> str:
    return {"rdfs:label": "name"}.get(prop, prop)


def _answer(outcome: Outcome, name: _Namer) -> str:
    claim = outcome.claim
    values = [v for _, v in outcome.held]
    if values and claim.predicate == "name" and claim.subject != name.speaker:
        return f"That's {listing(values)}."  # "what is her name?"
    if values:
        facts = [clause(Claim(claim.subject, claim.predicate, v), name) for v in values]
        if claim.predicate in {"likes", "dislikes"} and len(values) > 1:
            return _cap(f"{clause(claim, name, listing([name(v) for v in values]))}.")
        return _cap(f"{listing(facts)}.")
    if outcome.hearsay:
        said = [f"{name.person(who, 'someone')} told me {clause(claim, name, v)}"
                for who, v in outcome.hearsay[:3]]
        return _cap(f"{listing(said)}.")
    return _unknown_answer(claim, name)


def _unknown_answer(claim: Claim, name: _Namer) -> str:
    who = name.person(claim.subject, name(claim.subject))
    match claim.predicate:
        case "name" if claim.subject == name.speaker:
            return "I don't know your name yet. What is it?"
        case "name":
            return f"I don't know {name.person(claim.subject, 'their')}'s name.".replace("their's", "their")
        case "belongsTo":
            return f"I don't know whose {name(claim.subject).removeprefix('the ')} is."
        case "isIn" | "isOn":
            thing = name(claim.subject)
            return f"I don't know where {thing} {_be(thing)}."
        case "likes":
            return f"I don't know what {who} {'like' if who == 'you' else 'likes'}."
        case _:
            return f"I don't know what {who} {'dislike' if who == 'you' else 'dislikes'}."


def confirmation(settled: Settled, snapshot: Snapshot, speaker: str) -> str:
    """The reply to a turn's claims, one sentence each, in order, without repeats."""
    name = _Namer(snapshot, speaker, settled.names)
    sentences: list[str] = []
    for said in dict.fromkeys(sentence(o, name) for o in settled.outcomes):
        if sentences and sentences[-1].startswith(_OK) and said.startswith(_OK):  # "OK, a and b."
            sentences[-1] = f"{sentences[-1][:-1]} and {said[len(_OK):]}"
        else:
            sentences.append(said)
    return " ".join(sentences)
