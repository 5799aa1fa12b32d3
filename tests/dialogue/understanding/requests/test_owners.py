"""Whose a role's phrase says its place is, and "my X" of several none of them the speaker's."""

from dialogue.reference.resolution import THING
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.requests.owners import none_yours, whose
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb

KIM = "person_kim"


def _room() -> KB:
    return scene_kb(
        None, f"{KIM} rdf:type Human", f'{KIM} rdfs:label "Kim"', f"myself sees {KIM}",
        "person_al rdf:type Human", 'person_al rdfs:label "Al"', "myself sees person_al",
        "desk_k rdf:type Artifact", 'desk_k rdfs:label "desk"', f"desk_k belongsTo {KIM}", "myself sees desk_k",
        "desk_a rdf:type Artifact", 'desk_a rdfs:label "desk"', "desk_a belongsTo person_al", "myself sees desk_a",
        "mug_1 rdf:type Artifact", 'mug_1 rdfs:label "mug"', "mug_1 hasColor red", "myself sees mug_1",
        "mug_2 rdf:type Artifact", 'mug_2 rdfs:label "mug"', "mug_2 hasColor blue", "myself sees mug_2",
    )  # fmt: skip


def test_a_place_said_with_whose_it_is_names_the_owner() -> None:
    reader = Interpreter(lexicon_of(_room()), KIM)
    assert whose(reader, ("my", "desk"), THING) == (("desk",), KIM)
    assert whose(reader, ("the", "desk"), THING) == (("the", "desk"), None)  # no possessive: no one's


def test_my_x_of_several_none_mine_is_said_before_asking_which() -> None:
    reader = Interpreter(lexicon_of(_room()), KIM)
    asked = Outcome("Which mug do you mean: the red one or the blue one?", clarify=True)
    assert none_yours(reader, asked, ("mug",), THING).reply.startswith("As far as I know, neither mug is yours.")
    said = Outcome("OK.")  # not a question: nothing to say first
    assert none_yours(reader, said, ("mug",), THING) is said
