"""Answers to questions about the situation: where things are, who is somewhere."""

from kb import KB
from tests.dialogue.conftest import scene_kb
from tests.dialogue.understanding.test_interpret import say


def test_where_is_a_name_several_share_says_where_each_is(office: KB) -> None:
    reply = say(office, "where is the mug?").reply
    assert "green mug" in reply and "yellow mug" in reply


def test_where_is_one_in_sight_and_one_not_names_both() -> None:
    kb = scene_kb(
        None, "myself rdf:type Robot",
        "hall rdf:type ZoneOfInterest", 'hall rdfs:label "hall"',
        "shed rdf:type ZoneOfInterest", 'shed rdfs:label "shed"',
        "cup_r rdf:type dbr:Cup", 'cup_r rdfs:label "cup"', "cup_r hasColor red", "cup_r isIn hall",
        "myself sees cup_r",
        "cup_g rdf:type dbr:Cup", 'cup_g rdfs:label "cup"', "cup_g hasColor green", "cup_g isIn shed",
    )  # fmt: skip
    reply = say(kb, "where's the cup?").reply
    assert "red cup" in reply and "green cup" in reply and "shed" in reply


def test_who_is_at_a_thing_names_whom_the_kb_puts_next_to_it() -> None:
    kb = scene_kb(
        None, "myself rdf:type Robot",
        "hall rdf:type ZoneOfInterest", 'hall rdfs:label "hall"',
        "desk_1 rdf:type Artifact", 'desk_1 rdfs:label "writing desk"', "desk_1 isIn hall",
        "person_ina rdf:type Human", 'person_ina rdfs:label "Ina"', "person_ina isIn hall",
        "person_ina isNextTo desk_1", "myself sees person_ina",
        "lamp_1 rdf:type Artifact", 'lamp_1 rdfs:label "lamp"', "lamp_1 isIn hall",
        "shed rdf:type ZoneOfInterest", 'shed rdfs:label "shed"',
        "bench_1 rdf:type Artifact", 'bench_1 rdfs:label "bench"', "bench_1 isIn shed",
    )  # fmt: skip
    assert say(kb, "who is sitting at the writing desk?").reply == "At the writing desk, there is Ina."
    assert say(kb, "who is by the bench").reply == "I don't know of anyone at the bench."
    # nobody by it, but someone in its room: said as such
    assert say(kb, "who is by the lamp").reply == (
        "I don't know of anyone right at the lamp, but in the hall, where it is, there is Ina.")


def test_what_you_see_cut_short_names_what_things_are_on_first() -> None:
    small = [f for n in range(14) for f in (f"t{n:02} rdf:type Artifact", f't{n:02} rdfs:label "trinket {n}"',
                                           f"t{n:02} isOn zsofa", f"myself sees t{n:02}")]  # fmt: skip
    kb = scene_kb(None, "myself rdf:type Robot", "zsofa rdf:type dbr:Couch", 'zsofa rdfs:label "sofa"',
                  "myself sees zsofa", *small)  # fmt: skip
    reply = say(kb, "what can you see?").reply
    assert reply.startswith("I see the sofa, ") and reply.endswith("and 3 more things.")


def _club() -> KB:
    return scene_kb(
        None, "myself rdf:type Robot",
        "room rdf:type ZoneOfInterest", 'room rdfs:label "clubhouse"', "myself isIn room",
        "loft rdf:type ZoneOfInterest", 'loft rdfs:label "sail loft"',
        "bar rdf:type dbr:Table_(furniture)", 'bar rdfs:label "bar"', "bar isIn room", "myself sees bar",
        "desk rdf:type dbr:Table_(furniture)", 'desk rdfs:label "chart table"', "desk isIn room",
        "myself sees desk",
        "cup_b rdf:type dbr:Cup", 'cup_b rdfs:label "blue cup"', "cup_b isOn bar", "myself sees cup_b",
        "cup_w rdf:type dbr:Cup", 'cup_w rdfs:label "white cup"', "cup_w isOn bar", "myself sees cup_w",
        "book_1 rdf:type dbr:Book", 'book_1 rdfs:label "race log"', "book_1 isOn desk", "myself sees book_1",
        "pail rdf:type dbr:Bucket", 'pail rdfs:label "bailer"', "pail isIn loft",
    )  # fmt: skip


def test_which_of_a_kind_are_on_a_place_names_only_those() -> None:
    kb = _club()
    assert say(kb, "which cups are on the bar?").reply == "On the bar, there are the blue cup and the white cup."
    assert say(kb, "which cups are on the chart table?").reply == "I don't know of any cups on the chart table."
    # in a room, on what stands there: each said where
    assert say(kb, "which cups are in the clubhouse?").reply == (
        "In the clubhouse, there are the blue cup on the bar and the white cup on the bar.")  # fmt: skip


def test_which_of_a_kind_the_kb_does_not_know_is_not_answered() -> None:
    outcome = say(_club(), "which gizmos are on the bar?")
    assert outcome.intent is None and not outcome.understood


def test_how_many_on_a_place_counts_only_those_there() -> None:
    kb = _club()
    assert say(kb, "how many cups are on the bar?").reply == "I see two cups: the blue cup and the white cup."
    assert say(kb, "count the cups on the chart table").reply == "I don't see any cups on the chart table."
    assert say(kb, "how many cups are in the clubhouse?").reply.startswith("I see two cups")
