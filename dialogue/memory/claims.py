"""What a person tells the robot (or asks it) about the world, as claims whose referents are KB ids.

A claim is a statement (`object` given: "the red mug is mine" -> `mug_red belongsTo person_bob`) or
a question (`object` None: "what does Alice like?" -> `person_alice likes ?`). The predicates are a
closed table: each names its KB property, the kinds of entity its subject and object may be, and
which values a new one replaces (a name replaces a name, a place a place, a liking its opposite).

Claims come from the rules (dialogue.understanding.statements.grammar) or from a model's answer
(`facts`, whose ids are grounded here exactly as intent roles are: an id of the snapshot, or a name
that resolves to one entity of the right kind; an ambiguous one becomes a clarifying question, an
unknown one an `AnswerError` that the repair request sends back).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.english import tokens
from dialogue.reference.grounding import Kind
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import ANYWHERE, PERSON, resolve_id
from dialogue.schema import AnswerError, FactClaim
from dialogue.understanding.replies import say
from dialogue.understanding.said import Said
from dialogue.understanding.statements.names import clean_name

#: How the object of a claim is read: a KB entity id, words naming a kind (a class of the KB,
#: found when the claim is learnt: "tea"), or a name (a literal: "Bob").
ObjectForm = Literal["entity", "kind", "text"]
_HOLDERS: frozenset[Kind] = frozenset({"thing", "person"})
_PLACES: frozenset[Kind] = frozenset({"zone", "thing"})
#: What a person may like: anyone or anything of the situation, the robot too ("I like you").
_LIKED: frozenset[Kind] = ANYWHERE | {"robot"}


@dataclass(frozen=True)
class Predicate:
    """One row of the table: the answer's word for it and the KB property it writes."""

    name: str
    property: str
    subjects: frozenset[Kind]
    #: Kinds an entity object may be; None: the object is a name (a literal).
    objects: frozenset[Kind] | None
    #: The object may also be a kind (a class of the KB) rather than an entity.
    kinds: bool = False
    #: The properties a new value replaces: of the same subject, or of the same subject and object
    #: (`per_object`: "I hate tea" replaces "I like tea", not "I like coffee").
    replaces: tuple[str, ...] = ()
    per_object: bool = False


PREDICATES: dict[str, Predicate] = {
    p.name: p
    for p in (
        Predicate("name", "rdfs:label", PERSON, None, replaces=("rdfs:label",)),
        Predicate("belongsTo", "belongsTo", frozenset({"thing"}), PERSON, replaces=("belongsTo",)),
        Predicate("isIn", "isIn", _HOLDERS, _PLACES, replaces=("isIn", "isOn")),
        Predicate("isOn", "isOn", _HOLDERS, _PLACES, replaces=("isIn", "isOn")),
        Predicate("likes", "likes", PERSON, _LIKED, kinds=True, replaces=("likes", "dislikes"),
                  per_object=True),
        Predicate("dislikes", "dislikes", PERSON, _LIKED, kinds=True, replaces=("likes", "dislikes"),
                  per_object=True),
    )
}
#: The predicate of each KB property the table writes.
BY_PROPERTY = {p.property: p for p in PREDICATES.values()}


@dataclass(frozen=True)
class Claim:
    """A grounded statement or question: `subject` is a KB entity id; `object` is read as `form`
    says, or None for a question."""

    subject: str
    predicate: str
    object: str | None
    form: ObjectForm = "entity"
    #: For a kind: the one entity of the situation its words also name, taken when the KB has no
    #: such kind ("I like the radio" said as "I like radio").
    fallback: str | None = None

    @property
    def spec(self) -> Predicate:
        return PREDICATES[self.predicate]

    @property
    def asks(self) -> bool:
        return self.object is None


@dataclass(frozen=True)
class GroundedFacts:
    claims: tuple[Claim, ...]
    #: A question telling ambiguous referents apart; the claims are then empty.
    question: str | None = None
    #: Why nothing can be learnt from the answer (a speaker who is nobody of the KB).
    refusal: str | None = None


def ground_facts(facts: Sequence[FactClaim], lexicon: Lexicon, speaker: str) -> GroundedFacts:
    """A model's `facts` to claims (AnswerError saying what is wrong, for the repair request)."""
    claims: list[Claim] = []
    for n, fact in enumerate(facts):
        spec = PREDICATES.get(fact.predicate or "")
        if spec is None:
            raise AnswerError(f"facts[{n}].predicate {fact.predicate!r} is not one of {list(PREDICATES)}")
        subject, question = _entity(lexicon, speaker, fact.subject, spec.subjects, f"facts[{n}].subject")
        if question is not None:
            return GroundedFacts((), question)
        value = (fact.object or "").strip()
        if not value:
            claims.append(Claim(subject, spec.name, None))
            continue
        if spec.objects is None:
            name = clean_name(Said(lexicon.lang, value))
            if not name or value in lexicon.snapshot.entities:
                raise AnswerError(f"facts[{n}].object {fact.object!r} is not a name: give the name itself")
            claims.append(Claim(subject, spec.name, name, "text"))
            continue
        speaker_said = value.lower() in lexicon.lang.words.speaker_in_fact
        if spec.kinds and value not in lexicon.snapshot.entities and not speaker_said:
            # words: a kind first ("tea")
            found = resolve_id(lexicon, value, spec.objects).one
            words = " ".join(tokens(value))
            claims.append(Claim(subject, spec.name, words, "kind", found.id if found is not None else None))
            continue
        obj, question = _entity(lexicon, speaker, value, spec.objects, f"facts[{n}].object")
        if question is not None:
            return GroundedFacts((), question)
        if obj == subject:
            # A small model made to write "facts" on every turn fills it with "the apple isOn the
            # apple"; no one says that, so it goes back for repair rather than into the memory.
            raise AnswerError(f"facts[{n}] says {subject!r} {spec.name} itself: "
                              "give only facts the person said, or null")
        claims.append(Claim(subject, spec.name, obj))
    who = lexicon.snapshot.get(speaker)
    if (who is None or who.kind != "person") and any(not c.asks or speaker == c.subject for c in claims):
        # nobody to hold the belief, or to ask about (as for intents; the robot, speaking as
        # `myself`, is no one to learn from)
        return GroundedFacts((), refusal=say(lexicon.lang, "sorry.unknown_speaker"))
    return GroundedFacts(tuple(claims))


def _entity(
    lexicon: Lexicon, speaker: str, value: str | None, kinds: frozenset[Kind], where: str
) -> tuple[str, str | None]:
    """An id of `kinds` (the speaker for "me"), or a clarifying question; AnswerError otherwise."""
    text = (value or "").strip()
    # An id first: "myself" is the robot's (ROS4HRI), not the speaker saying "myself".
    if "person" in kinds and (text == speaker or (lexicon.snapshot.get(text) is None
                                                  and text.lower() in lexicon.lang.words.speaker_in_fact)):
        return speaker, None
    found = resolve_id(lexicon, text, kinds) if text else None
    if found is not None and found.one is not None:
        return found.one.id, None
    if found is not None and found.ambiguous:
        return "", clarifying_question(lexicon.lang, lexicon.snapshot, found.matches)
    allowed = sorted(e.id for e in lexicon.snapshot.entities.values() if e.kind in kinds)[:30]
    raise AnswerError(f"{where} {value!r} is not the id of a {'/'.join(sorted(kinds))} in the situation; "
                      f"use one of {allowed}")
