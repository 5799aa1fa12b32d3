"""Where a thing or person is among places, and "is X in Y?"."""

from dialogue.understanding.questions.placed import held
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb
from tests.dialogue.understanding.test_interpret import say


def _shed() -> KB:
    return scene_kb(
        None, "myself rdf:type Robot",
        "shed rdf:type ZoneOfInterest", 'shed rdfs:label "boat shed"', "myself isIn shed",
        "slip rdf:type ZoneOfInterest", 'slip rdfs:label "slipway"',
        "bench rdf:type dbr:Table_(furniture)", 'bench rdfs:label "workbench"', "bench isIn shed",
        "myself sees bench",
        "rack rdf:type dbr:Shelf_(storage)", 'rack rdfs:label "oar rack"', "rack isIn shed", "myself sees rack",
        "tray rdf:type cyc:Tray", 'tray rdfs:label "tray"', "tray isOn bench", "myself sees tray",
        "flask rdf:type Bottle", 'flask rdfs:label "flask"', "flask isOn tray", "myself sees flask",
        "kayak rdf:type dbr:Kayak", 'kayak rdfs:label "red kayak"', "kayak isIn slip",
        "canoe rdf:type dbr:Canoe", 'canoe rdfs:label "green canoe"', "canoe isIn shed", "myself sees canoe",
        "torch rdf:type dbr:Flashlight", 'torch rdfs:label "torch"', "torch isOn rack", "myself sees torch",
    )  # fmt: skip


def test_a_thing_is_held_by_what_holds_what_it_is_on() -> None:
    snapshot = lexicon_of(_shed()).snapshot
    flask = snapshot.get("flask")
    assert flask is not None
    assert held(snapshot, flask, "tray") and held(snapshot, flask, "bench") and held(snapshot, flask, "shed")
    assert not held(snapshot, flask, "rack") and not held(snapshot, flask, "slip")


def test_a_thing_asked_about_in_the_wrong_place_is_said_where_it_is() -> None:
    kb = _shed()
    assert say(kb, "Is the red kayak in the shed?").reply == "No, as far as I know the red kayak is in the slipway."
    assert say(kb, "is the torch on the workbench").reply == "No, as far as I know the torch is on the oar rack."


def test_a_thing_where_it_is_asked_about_is_not_said_elsewhere() -> None:
    kb = _shed()
    assert say(kb, "is the green canoe in the boat shed?").reply.startswith("Yes")
    # on a tray on the workbench: there, never said to be somewhere else
    assert "as far as I know" not in say(kb, "is the flask on the workbench?").reply
    assert "as far as I know" not in say(kb, "is the flask in the boat shed?").reply
