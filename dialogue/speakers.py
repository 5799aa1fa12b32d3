"""Speakers are people of the KB, so that an intent naming the speaker names a KB entity.

Perception tells the KB who is around; a speaker it has not reported (a Rasa sender, a chat user)
is made a person on their first turn, as perception would have said: `<id> rdf:type Human` in the
robot's model, one commit. A speaker the KB knows already is never retyped. ROS4HRI's source
constants (`__unknown_agent__`...), the chat roles (`__system__`, `__assistant__`) and ids that are
no KB name are nobody to ground: they are never added, and no intent names them.
"""

from __future__ import annotations

from rdflib import RDF, URIRef

from dialogue.history import ASSISTANT_USER_ID, SYSTEM_USER_ID
from dialogue.intents import SOURCES
from kb import KbError
from kb.protocol import KnowledgeBase
from kb.terms import ORO, format_triple, parse_name

NOT_PEOPLE = SOURCES | {SYSTEM_USER_ID, ASSISTANT_USER_ID}
PERSON_CLASS = URIRef(ORO + "Human")  # one of grounding.PERSON_CLASSES


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
