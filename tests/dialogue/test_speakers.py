"""Speakers are people of the KB: an unknown id becomes one; an id naming what is no person is refused."""

from __future__ import annotations

import pytest

from dialogue import intents as I
from dialogue.speakers import NotAPerson, admit, check_speaker
from kb import KB


@pytest.fixture
def kb() -> KB:
    kb = KB()
    kb.update(["myself rdf:type Robot", "cup rdf:type dbr:Cup", 'cup rdfs:label "cup"', "cup isOn table_1",
               "table_1 rdf:type dbr:Table_(furniture)", "hall rdf:type ZoneOfInterest", 'hall rdfs:label "hall"',
               "person_ana rdf:type Human", "book_1 belongsTo person_tom", "sofa_1 isIn hall"])
    return kb


@pytest.mark.parametrize(("speaker", "says"), [
    ("cup", "'cup' names the cup, a thing of the KB, not a person"),
    ("table_1", "names table_1, a thing of the KB"),
    ("hall", "names the hall, a place of the KB"),
    ("myself", "names the robot itself"),
    ("dbr:Cup", "'dbr:Cup' names a class of the KB, not a person"),
    ("Human", "names a class of the KB"),
    ("dbr:Table_(furniture)", "names a class of the KB"),
    ("isOn", "'isOn' names a property of the KB, not a person"),
    ("belongsTo", "names a property of the KB"),
    ("rdf:type", "'rdf:type' is an RDF/OWL keyword, not a person"),
    ("owl:Thing", "is an RDF/OWL keyword"), ("rdfs:label", "is an RDF/OWL keyword"),
    ("xsd:string", "is an RDF/OWL keyword"),
])
def test_an_id_naming_what_is_no_person_is_refused_and_never_added(kb: KB, speaker: str, says: str) -> None:
    revision = kb.revision
    with pytest.raises(NotAPerson) as refused:
        check_speaker(kb, speaker)
    assert says in str(refused.value) and str(refused.value).startswith("user_id ")
    with pytest.raises(NotAPerson, match=r"^sender "):
        check_speaker(kb, speaker, "sender")
    assert kb.revision == revision


@pytest.mark.parametrize("speaker", ["person_ana", "person_tom", "person_new", "u", I.UNKNOWN_AGENT, "__system__",
                                     "__assistant__", "not a name"])
def test_people_new_or_known_and_the_chat_roles_pass(kb: KB, speaker: str) -> None:
    check_speaker(kb, speaker)  # person_tom: known as an owner only, which a person may be


def test_a_new_person_is_added_once(kb: KB) -> None:
    assert admit(kb, "person_new") and kb.exist(["person_new rdf:type Human"])
    assert not admit(kb, "person_new") and not admit(kb, "person_ana")
