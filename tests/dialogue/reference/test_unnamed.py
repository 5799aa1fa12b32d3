"""What a phrase names when no name of the KB settles it: a measure's thing, a container's contents,
the adjective a comparative compares by, a part of a label, qualifiers alone."""

from dialogue.reference import unnamed
from dialogue.reference.lexicon import norm
from dialogue.reference.resolution import THING
from kb import KB
from tests.dialogue.conftest import english, lexicon_of


def test_a_measure_names_the_thing_measured() -> None:
    assert unnamed.thing_measured(english(), ["a", "pair", "of", "glasses"]) == ("glasses",)
    assert unnamed.thing_measured(english(), ["the", "glasses"]) == ()


def test_a_container_names_what_it_holds() -> None:
    words = ["a", "can", "of", "beer"]
    assert unnamed.thing_held(english(), words, norm(words)) == ("beer",)
    assert unnamed.thing_held(english(), ["the", "beer"], norm(["the", "beer"])) == ()


def test_a_comparative_compares_by_its_adjective() -> None:
    assert unnamed.compared(english(), "bigger") == "big"
    assert unnamed.compared(english(), "cup") == "cup"


def test_qualifiers_alone_name_the_things_they_all_hold_for(office: KB) -> None:
    lexicon = lexicon_of(office)
    green = unnamed.by_qualifiers(lexicon, ["green"], THING)
    assert "mug_green" in {e.id for e in green}
    assert all("green" in lexicon.attributes.get(e.id, frozenset()) for e in green)
