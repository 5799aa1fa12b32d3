import pytest

from dialogue.reference.english import tokens
from dialogue.reference.grounding import Kind
from dialogue.reference.resolution import resolve, resolve_id
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb

THING: frozenset[Kind] = frozenset({"thing"})
PERSON: frozenset[Kind] = frozenset({"person"})
ZONE: frozenset[Kind] = frozenset({"zone"})
PLACE: frozenset[Kind] = frozenset({"zone", "thing"})


def ids(kb: KB, phrase: str, kinds: frozenset[Kind] = THING) -> list[str]:
    return [e.id for e in resolve(lexicon_of(kb), tokens(phrase), kinds).matches]


@pytest.mark.parametrize(
    ("phrase", "expected"),
    [
        ("the cup", ["cup_1"]),  # class label
        ("the cookbook", ["book_1"]),  # instance label
        ("a book", ["book_1"]),  # class of a labelled instance
        ("some fruit", ["apple_1"]),  # hypernym through the class hierarchy
        ("the sponge", ["sponge_1"]),  # label of an instance of an unlabelled class
        ("cup_1", ["cup_1"]),  # id
        ("the cup on the table", ["cup_1"]),  # support
        ("the kitchen table", ["table_1"]),  # zone as a qualifier
        ("the cups", ["cup_1"]),  # plural
        ("the banana", []),
        ("the cup on the shelf", []),  # wrong support rules it out
    ],
)
def test_kitchen_phrases(kitchen: KB, phrase: str, expected: list[str]) -> None:
    assert ids(kitchen, phrase) == expected


def test_adjectives_from_labels_and_colour_properties(cups: KB) -> None:
    assert ids(cups, "the red cup") == ["cup_red"]
    assert ids(cups, "the blue one cup") == ["cup_blue"]
    assert ids(cups, "the white phone") == ["phone_b"]
    assert ids(cups, "the green phone") == []
    assert set(ids(cups, "the cup")) == {"cup_red", "cup_blue"}


def test_whole_words_only() -> None:
    kb = scene_kb(
        "kitchen",
        "cupboard_1 rdf:type Artifact",
        'cupboard_1 rdfs:label "cupboard"',
        "myself sees cupboard_1",
    )
    assert ids(kb, "the cup") == ["cup_1"]
    assert ids(kb, "the cupboard") == ["cupboard_1"]


def test_head_noun_of_a_label_names_the_thing(office: KB) -> None:
    assert set(ids(office, "the mug")) == {"mug_green", "mug_yellow"}
    assert ids(office, "the yellow mug") == ["mug_yellow"]


def test_visible_entities_are_preferred() -> None:
    kb = scene_kb("kitchen", "cup_9 rdf:type dbr:Cup", "cup_9 isIn bedroom")
    assert ids(kb, "the cup") == ["cup_1"]
    assert ids(kb, "the cup in the bedroom") == ["cup_9"]


def test_kinds_filter_people_and_places(kitchen: KB) -> None:
    lex = lexicon_of(kitchen)
    assert resolve(lex, ["tom"], PERSON).one is not None
    assert resolve(lex, ["tom"], THING).matches == ()
    assert resolve_id(lex, "kitchen", ZONE).one is not None
    assert resolve_id(lex, "evil_1", THING).matches == ()
    assert resolve_id(lex, "person_alice", THING).matches == ()


def _pantry() -> KB:
    return scene_kb(None, "c1 rdf:type cyc:Drink", 'c1 rdfs:label "cider"', "myself sees c1",
                    "m1 rdf:type cyc:Food", 'm1 rdfs:label "soup"', "myself sees m1",
                    "j1 rdf:type Artifact", 'j1 rdfs:label "jam jar"', "myself sees j1",
                    "r1 rdf:type Artifact", 'r1 rdfs:label "rain coat"', "myself sees r1")  # fmt: skip


@pytest.mark.parametrize(
    ("phrase", "expected"),
    [
        ("the cider bottles", ["c1"]),  # no bottle: the container names what it holds
        ("a tin of soup", ["m1"]),
        ("the jam jar", ["j1"]),  # a jar the KB has is the jar
        ("the raincoat", ["r1"]),  # a two-word name said as one word
        ("the wine bottle", []),  # nothing holds wine: nothing, not the cider
        ("a box of raincoat", []),  # a box holds food or drink, not a coat
    ],
)
def test_containers_and_names_said_as_one_word(phrase: str, expected: list[str]) -> None:
    assert ids(_pantry(), phrase) == expected


def _shop(*facts: str) -> KB:
    return scene_kb(
        None,
        "myself rdf:type Robot",
        "kim rdf:type Human", 'kim rdfs:label "Kim"', "myself sees kim",
        *facts,
    )  # fmt: skip


def test_a_general_name_names_a_kind_and_ownership_picks_among_them() -> None:
    kb = _shop(
        "tote_1 rdf:type Artifact", 'tote_1 rdfs:label "satchel"', "tote_1 belongsTo kim", "myself sees tote_1",
        "sack_1 rdf:type Artifact", 'sack_1 rdfs:label "carrier bag"', "myself sees sack_1",
    )  # fmt: skip
    lex = lexicon_of(kb)
    # the KB's own "bag" first; whose it is comes before that
    assert [e.id for e in resolve(lex, tokens("the bag"), THING).matches] == ["sack_1"]
    assert [e.id for e in resolve(lex, tokens("my bag"), THING, owner="kim").matches] == ["tote_1"]
    kb.close()


def test_a_kind_never_names_another_kind_of_the_same_general_name() -> None:
    kb = _shop("pop_1 rdf:type Artifact", 'pop_1 rdfs:label "lemonade"', "myself sees pop_1")
    assert ids(kb, "a drink") == ["pop_1"]
    assert ids(kb, "the smoothie") == []  # both drinks, but a smoothie is no lemonade
    kb.close()


def test_the_kbs_own_name_beats_the_lexicon_files() -> None:
    kb = _shop(
        "wc_1 rdf:type ZoneOfInterest", 'wc_1 rdfs:label "toilets"',
        "bath_1 rdf:type ZoneOfInterest", 'bath_1 rdfs:label "bathroom"',
        "cart_1 rdf:type Artifact", 'cart_1 rdfs:label "shopping cart"', "myself sees cart_1",
    )  # fmt: skip
    assert ids(kb, "the bathroom", ZONE) == ["bath_1"]
    assert sorted(ids(kb, "the loo", ZONE)) == ["bath_1", "wc_1"]  # either may be meant: asked
    assert ids(kb, "the trolley") == ["cart_1"]  # British for the cart
    kb.close()
    kb = _shop("wc_1 rdf:type ZoneOfInterest", 'wc_1 rdfs:label "toilets"')
    assert ids(kb, "the bathroom", ZONE) == ["wc_1"]  # none labelled so: the toilets it may be
    kb.close()


def test_top_is_a_word_of_a_name_but_not_of_on_top_of() -> None:
    kb = _shop(
        "sh_1 rdf:type Artifact", 'sh_1 rdfs:label "top shelf"', "myself sees sh_1",
        "sh_2 rdf:type Artifact", 'sh_2 rdfs:label "bottom shelf"', "myself sees sh_2",
        "jar_1 rdf:type Artifact", 'jar_1 rdfs:label "jar"', "jar_1 isOn sh_2", "myself sees jar_1",
    )  # fmt: skip
    assert ids(kb, "the top shelf") == ["sh_1"]
    assert ids(kb, "the jar on top of the bottom shelf") == ["jar_1"]
    kb.close()


def test_the_garbage_is_the_bin() -> None:
    kb = _shop("b_1 rdf:type Artifact", 'b_1 rdfs:label "trash can"', "myself sees b_1")
    assert ids(kb, "the garbage") == ids(kb, "the rubbish") == ["b_1"]
    kb.close()


@pytest.mark.parametrize(
    ("phrase", "expected"),
    [
        ("a pair of safety goggles", ["goggles_1"]),
        ("a roll of tape", ["tape_1"]),
        ("a couple of the goggles", ["goggles_1"]),
        ("a pair of gloves", []),  # no gloves: a measure of nothing is nothing
    ],
)
def test_a_measure_of_a_thing_names_the_thing(phrase: str, expected: list[str]) -> None:
    kb = scene_kb(
        None,
        "goggles_1 rdf:type Artifact", 'goggles_1 rdfs:label "safety goggles"', "myself sees goggles_1",
        "tape_1 rdf:type Artifact", 'tape_1 rdfs:label "tape"', "myself sees tape_1",
    )  # fmt: skip
    assert ids(kb, phrase) == expected


def _many(count: int, label: str, *facts: str) -> KB:
    """A shop with ``count`` unseen things labelled ``label`` in its store (past the count where
    resolution looks at the seen ones first) and the given facts."""
    things = [f for i in range(count) for f in (f"{label}_{i} rdf:type Artifact", f'{label}_{i} rdfs:label "{label}"',
                                                 f"{label}_{i} isIn store")]  # fmt: skip
    return _shop("store rdf:type ZoneOfInterest", 'store rdfs:label "store"', *things, *facts)


def test_a_word_naming_hundreds_of_things_answers_as_for_a_few() -> None:
    kb = _many(
        150, "apple",
        "seen_a rdf:type Artifact", 'seen_a rdfs:label "apple"', "myself sees seen_a",
        "seen_b rdf:type Artifact", 'seen_b rdfs:label "apple"', "myself sees seen_b",
        "kims rdf:type Artifact", 'kims rdfs:label "apple"', "kims belongsTo kim", "kims isIn store",
        "pip rdf:type Human", 'pip rdfs:label "Apple"',
    )  # fmt: skip
    lex = lexicon_of(kb)
    assert ids(kb, "the apple") == ["seen_a", "seen_b"]  # the ones in sight
    assert [e.id for e in resolve(lex, tokens("the apple"), THING, owner="kim").matches] == ["kims"]  # unseen
    assert [e.id for e in resolve(lex, tokens("apple"), PERSON).matches] == ["pip"]
    kb.close()
    kb = _many(150, "apple")
    assert len(ids(kb, "the apple")) == 150  # none in sight: all of them, to be asked about
    kb.close()


def test_among_hundreds_the_kbs_own_name_still_beats_a_seen_synonym() -> None:
    kb = _many(100, "fridge", "cold_1 rdf:type Artifact", 'cold_1 rdfs:label "refrigerator"', "myself sees cold_1")
    assert len(ids(kb, "the fridge")) == 100 and "cold_1" not in ids(kb, "the fridge")
    assert ids(kb, "the refrigerator") == ["cold_1"]
    kb.close()


def test_a_thing_named_by_all_the_words_comes_before_one_they_describe() -> None:
    kb = _shop(
        "kitchen rdf:type ZoneOfInterest", 'kitchen rdfs:label "kitchen"',
        "counter_1 rdf:type dbr:Table_(furniture)", 'counter_1 rdfs:label "counter"', "counter_1 isIn kitchen",
        "myself sees counter_1",
        "table_1 rdf:type dbr:Table_(furniture)", 'table_1 rdfs:label "kitchen table"', "myself sees table_1",
    )  # fmt: skip
    assert ids(kb, "the kitchen table") == ["table_1"]
    assert sorted(ids(kb, "the table")) == ["counter_1", "table_1"]
    kb.close()


def test_the_ones_on_a_place_are_never_the_place() -> None:
    kb = _shop("bench_1 rdf:type Artifact", 'bench_1 rdfs:label "bench"', "myself sees bench_1",
               "lev_1 rdf:type Artifact", 'lev_1 rdfs:label "tyre levers"', "lev_1 isOn bench_1",
               "myself sees lev_1")  # fmt: skip
    assert "bench_1" not in ids(kb, "the ones on the bench")
    assert ids(kb, "the bench") == ["bench_1"]
    kb.close()


@pytest.mark.parametrize(("phrase", "expected"), [("the bigger jug", ["jug_big"]), ("the smallest jug", ["jug_small"])])
def test_a_comparative_qualifies_by_its_adjective(phrase: str, expected: list[str]) -> None:
    kb = _shop("jug_big rdf:type Artifact", 'jug_big rdfs:label "big jug"', "myself sees jug_big",
               "jug_small rdf:type Artifact", 'jug_small rdfs:label "small jug"', "myself sees jug_small")  # fmt: skip
    assert ids(kb, phrase) == expected
    assert ids(kb, "the bigger one") == ["jug_big"]
    kb.close()


def _flat(*facts: str) -> KB:
    """A flat with two towels (one in sight), a cabinet and a bathroom cabinet, a desk and a
    standing desk, an unlabelled sofa and a TV couch, and a bread shelf with a loaf on it."""
    return _shop(
        "kitchen rdf:type ZoneOfInterest", 'kitchen rdfs:label "kitchen"',
        "bathroom rdf:type ZoneOfInterest", 'bathroom rdfs:label "bathroom"',
        "towel_w rdf:type Cloth", 'towel_w rdfs:label "towel"', "towel_w isIn kitchen", "myself sees towel_w",
        "towel_b rdf:type Cloth", 'towel_b rdfs:label "towel"', "towel_b isIn bathroom",
        "cab_1 rdf:type cyc:FurniturePiece", 'cab_1 rdfs:label "cabinet"', "cab_1 isIn kitchen",
        "cab_2 rdf:type cyc:FurniturePiece", 'cab_2 rdfs:label "bathroom cabinet"', "cab_2 isIn bathroom",
        "desk_1 rdf:type dbr:Table_(furniture)", 'desk_1 rdfs:label "desk"', "desk_1 isIn kitchen",
        "desk_2 rdf:type dbr:Table_(furniture)", 'desk_2 rdfs:label "standing desk"', "desk_2 isIn kitchen",
        "sofa_1 rdf:type dbr:Couch", "sofa_1 isIn kitchen",
        "sofa_2 rdf:type dbr:Couch", 'sofa_2 rdfs:label "TV couch"', "sofa_2 isIn kitchen",
        "shelf_1 rdf:type dbr:Shelf_(storage)", 'shelf_1 rdfs:label "bread shelf"', "shelf_1 isIn kitchen",
        "loaf_1 rdf:type cyc:Food", 'loaf_1 rdfs:label "sourdough loaf"', "loaf_1 isOn shelf_1",
        "crisps_1 rdf:type cyc:Food", 'crisps_1 rdfs:label "ready salted crisps"', "crisps_1 isIn kitchen",
        "crisps_2 rdf:type cyc:Food", 'crisps_2 rdfs:label "cheese and onion crisps"', "crisps_2 isIn kitchen",
        *facts,
    )  # fmt: skip


@pytest.mark.parametrize(
    ("phrase", "expected"),
    [
        ("the desk", ["desk_1"]),  # called so, not only ending so
        ("the standing desk", ["desk_2"]),
        ("the cabinet", ["cab_1"]),
        ("the cabinet in the bathroom", ["cab_2"]),
        ("the tv couch", ["sofa_2"]),
    ],
)
def test_a_thing_called_exactly_what_is_said_is_that_thing(phrase: str, expected: list[str]) -> None:
    kb = _flat()
    assert ids(kb, phrase) == expected
    kb.close()


def test_a_kind_several_things_share_is_ambiguous_and_sight_chooses_only_when_asked_to() -> None:
    kb = _flat()
    lex = lexicon_of(kb)
    assert ids(kb, "the towel") == ["towel_w"]  # a place or a question: the one in sight
    fetched = resolve(lex, tokens("the towel"), THING, sight=False)
    assert sorted(e.id for e in fetched.matches) == ["towel_b", "towel_w"]  # a thing to fetch: asked
    # "cheese and onion crisps" are crisps as much as the "ready salted crisps" are
    assert sorted(ids(kb, "the crisps")) == ["crisps_1", "crisps_2"]
    assert ids(kb, "the cheese and onion crisps") == ["crisps_2"]
    kb.close()
    kb = _many(150, "apple", "seen_a rdf:type Artifact", 'seen_a rdfs:label "apple"', "myself sees seen_a")
    many = resolve(lexicon_of(kb), tokens("the apple"), THING, sight=False)
    assert [e.id for e in many.matches] == ["seen_a"]  # more than a question can list: the one in sight
    kb.close()


def test_the_place_a_thing_is_said_to_be_on_is_not_the_thing() -> None:
    kb = _flat()
    assert ids(kb, "the bread on the bread shelf") == []  # not the shelf: no bread is known
    assert ids(kb, "the loaf on the bread shelf") == ["loaf_1"]
    assert ids(kb, "the side of the bread shelf", PLACE) == ["shelf_1"]  # a part of it is it
    kb.close()


def test_a_thing_with_no_label_is_not_called_by_a_class_it_is_a_kind_of() -> None:
    kb = _flat(
        "pear_1 rdf:type dbr:Pear", "pear_1 isIn kitchen",
        "plant_1 rdf:type dbr:Plant", 'plant_1 rdfs:label "tomato plant"', "plant_1 isIn kitchen",
    )  # fmt: skip
    assert sorted(ids(kb, "the plant")) == ["pear_1", "plant_1"]  # a pear is no more "the plant"
    kb.close()


def test_a_cup_named_for_the_drink_it_holds_whether_said_apart_or_in_one_word() -> None:
    kb = scene_kb(None,
        "myself rdf:type Robot", "ed rdf:type Human", 'ed rdfs:label "Edna"', "hal rdf:type Human",
        "tc rdf:type dbr:Cup", 'tc rdfs:label "china teacup"', "tc belongsTo ed", "myself sees tc",
        "tm rdf:type dbr:Cup", 'tm rdfs:label "big tea mug"', "tm belongsTo hal", "myself sees tm",
        "bc rdf:type Artifact", 'bc rdfs:label "bookcase"', "myself sees bc",
    )  # fmt: skip
    lex = lexicon_of(kb)
    assert [e.id for e in resolve(lex, tokens("my tea"), owner="ed").matches] == ["tc"]
    assert {e.id for e in resolve(lex, tokens("the cup of tea")).matches} == {"tc", "tm"}  # asked
    assert {e.id for e in resolve(lex, tokens("the tea")).matches} == {"tc", "tm"}
    assert resolve(lex, tokens("the book")).matches == ()  # a bookcase holds no book it is named for
    kb.close()


def test_a_thing_whose_own_words_say_the_place_comes_before_one_only_in_that_place() -> None:
    kb = scene_kb(None,
        "myself rdf:type Robot", "k rdf:type ZoneOfInterest", 'k rdfs:label "shared kitchen"',
        "t rdf:type dbr:Table_(furniture)", 't rdfs:label "wobbly kitchen table"', "t isIn k", "myself sees t",
        "w rdf:type dbr:Table_(furniture)", 'w rdfs:label "worktop"', "w isIn k", "myself sees w",
    )  # fmt: skip
    lex = lexicon_of(kb)
    assert [e.id for e in resolve(lex, tokens("the kitchen table")).matches] == ["t"]
    assert {e.id for e in resolve(lex, tokens("the table in the kitchen")).matches} == {"t", "w"}  # asked
    kb.close()


def test_a_phrase_is_resolved_once_per_snapshot_and_kinds(kitchen: KB) -> None:
    lex = lexicon_of(kitchen)
    words = tokens("the cup on the table")
    first = resolve(lex, words, THING)
    assert [e.id for e in first.matches] == ["cup_1"]
    assert resolve(lex, list(words), THING) is first  # the same phrase asked again: looked up
    assert resolve(lex, words, PERSON).matches == ()  # other kinds: read anew
    assert resolve(lex, words, THING, owner="someone") is not first
    again = resolve(lexicon_of(kitchen), words, THING)  # another snapshot's lexicon: read anew
    assert again is not first and again == first
