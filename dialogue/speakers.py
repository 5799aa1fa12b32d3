"""Speakers are people of the KB, so that an intent naming the speaker names a KB entity.

Perception tells the KB who is around; a speaker it has not reported (a Rasa sender, a chat user)
is made a person on their first turn, as perception would have said: `<id> rdf:type Human` in the
robot's model, one commit. A speaker the KB knows already is never retyped. ROS4HRI's source
constants (`__unknown_agent__`...), the chat roles (`__system__`, `__assistant__`) and ids that are
no KB name are nobody to ground: they are never added, and no intent names them.

An id that names something of the KB that is no person — a thing, a place, the robot, a class, a
property, or a keyword of RDF, RDFS, OWL or XSD — is no speaker at all (`check_speaker`: refused
with `NotAPerson` before the turn, so that `rdf:type` never becomes a `Human` the robot greets and
`cup` never an agent with a mind of its own). An entity the KB types only by what a person also
is (an `Agent`, the owner of a thing) may still be one.
"""

from __future__ import annotations

from rdflib import OWL, RDF, RDFS, XSD, URIRef

from dialogue.errors import SessionError
from dialogue.history import ASSISTANT_USER_ID, SYSTEM_USER_ID
from dialogue.intents import SOURCES
from kb import KbError
from kb.protocol import KnowledgeBase
from kb.terms import ORO, format_triple, parse_name

NOT_PEOPLE = SOURCES | {SYSTEM_USER_ID, ASSISTANT_USER_ID}
PERSON_CLASS = URIRef(ORO + "Human")  # one of grounding.PERSON_CLASSES
_PERSON = "Human"
#: The vocabularies whose terms are the language of the KB, never anyone's id.
_KEYWORDS = tuple(str(ns) for ns in (RDF, RDFS, OWL, XSD))
_CLASS_TYPES = frozenset({"owl:Class", "rdfs:Class"})
_PROPERTY_TYPES = frozenset({"rdf:Property", "owl:ObjectProperty", "owl:DatatypeProperty",
                             "owl:AnnotationProperty", "owl:FunctionalProperty",
                             "owl:InverseFunctionalProperty", "owl:TransitiveProperty",
                             "owl:SymmetricProperty"})
#: What the refusal calls an entity of these classes (else "a thing").
_KINDS = {"Robot": "the robot itself", "ZoneOfInterest": "a place", "Zone": "a place"}


class NotAPerson(SessionError):
    """A speaker's id that names something of the KB that is no person; the message says what."""


def person_statement(speaker: str) -> str | None:
    """`<speaker> rdf:type Human` in statement syntax (the id parsed, then written back, never
    pasted), or None when the speaker cannot be a person of the KB."""
    if speaker in NOT_PEOPLE:
        return None
    try:
        term = parse_name(speaker, "speaker")
    except KbError:
        return None
    return format_triple((term, RDF.type, PERSON_CLASS))


def admit(kb: KnowledgeBase, speaker: str) -> bool:
    """Make `speaker` a person of the KB unless the KB knows it or it cannot be one; True when it
    was added. Blocking (a KB query, maybe a write); KbError when the KB refuses the write."""
    statement = person_statement(speaker)
    if statement is None or kb.classesof(speaker):
        return False
    kb.update([statement])
    return True


def check_speaker(kb: KnowledgeBase, speaker: str, what: str = "user_id") -> None:
    """Refuse (NotAPerson, naming the request's field `what`) an id that names something of the KB
    that is no person; a person, an id the KB does not know, a source constant or a chat role pass.
    Blocking: a few KB reads."""
    found = _not_a_person(kb, speaker)
    if found is not None:
        raise NotAPerson(f"{what} {speaker!r} {found}, not a person: a speaker's id is a person's, known "
                         "or new (e.g. person_bob)")


def _not_a_person(kb: KnowledgeBase, speaker: str) -> str | None:
    """What the id names when it is no person, else None."""
    if speaker in NOT_PEOPLE:
        return None
    try:
        term = parse_name(speaker, "speaker")
    except KbError:
        return None  # no KB name: never added, never named
    if str(term).startswith(_KEYWORDS):
        return "is an RDF/OWL keyword"
    classes = set(kb.classesof(speaker))
    if _PERSON in classes:
        return None
    written = f"<{term}>"  # the IRI itself: "a" in a pattern's predicate place is rdf:type
    if classes & _CLASS_TYPES or kb.exist([f"?x rdf:type {written}"]) \
            or kb.exist([f"{written} rdfs:subClassOf ?c"]):
        return "names a class of the KB"
    if classes & _PROPERTY_TYPES or kb.exist([f"?s {written} ?o"]):
        return "names a property of the KB"
    # What a person is too (an Agent, the owner of a thing) leaves the id a possible person.
    persons = {str(row["c"]) for row in kb.find([f"{_PERSON} rdfs:subClassOf ?c"])} | {"owl:Thing"}
    others = sorted(classes - persons)
    if not others:
        return None
    kind = next((_KINDS[c] for c in others if c in _KINDS), "a thing")
    if kind.startswith("the "):
        return f"names {kind}"
    labels = kb.find([f"{written} rdfs:label ?l"])
    named = f"the {labels[0]['l']}" if labels else speaker
    return f"names {named}, {kind} of the KB"
