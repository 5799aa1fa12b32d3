"""Keyboard and recogniser typos: corrected against the grammar's words and the KB's names, never a
correct word, never when two words are as close."""

import pytest

from dialogue import intents as I
from dialogue.understanding.speech import spelling
from dialogue.understanding.speech.spelling import corrected
from kb import KB
from tests.dialogue.conftest import english, lexicon_of, scene_kb
from tests.dialogue.understanding.test_interpret import say


def typing_cost(said: str, meant: str) -> float:
    return spelling.typing_cost(english(), said, meant)


def grammar_words() -> frozenset[str]:
    return spelling.grammar_words(english())


def _things(*labels: str) -> KB:
    facts = ["person_bob rdf:type Human", 'person_bob rdfs:label "Bob"', "myself sees person_bob"]
    for n, label in enumerate(labels):
        facts += [f"t{n} rdf:type Artifact", f't{n} rdfs:label "{label}"', f"myself sees t{n}"]
    return scene_kb(None, *facts)


@pytest.mark.parametrize(
    ("said", "meant", "cost"),
    [
        ("teh", "the", 0.8),  # two letters swapped
        ("cyp", "cup", 1.0),  # a neighbouring key
        ("plase", "please", 1.0),  # a letter missed
        ("plase", "place", 1.5),  # a key far away
        ("lego", "leg", 2.0),  # a short word with a letter more is another word
        ("thermoss", "thermos", 0.8),  # a letter typed twice
        ("helo", "hello", 0.8),  # a double letter typed once: cheaper than "help" (a key away)
        ("helo", "help", 1.0),
        ("thermis", "thermos", 1.0),
    ],
)
def test_typing_cost(said: str, meant: str, cost: float) -> None:
    assert typing_cost(said, meant) == cost


def test_grammar_words_come_from_the_word_lists_and_the_frames() -> None:
    assert {"please", "the", "bring", "towards", "behalf", "hold", "three"} <= grammar_words()


@pytest.mark.parametrize(
    ("text", "fixed", "referent"),
    [
        ("plase hand me teh thermos", "please hand me the thermos", False),
        ("pass me the thremos", "pass me the thermos", True),
        ("grab the dictionery please", "grab the dictionary please", True),
        ("Thremos on the ledge, pick it up.", "Thermos on the ledge, pick it up.", True),
    ],
)
def test_a_slip_is_corrected_to_the_one_word_it_is_close_to(text: str, fixed: str, referent: bool) -> None:
    spelled = corrected(text, lexicon_of(_things("thermos", "dictionary", "ledge")))
    assert spelled.text == fixed
    assert spelled.guessed is referent


@pytest.mark.parametrize(
    "text",
    [
        "bring me the lamp",  # an English word: not a slip of the lamb
        "greet Zed",  # an unknown name
        "pick up the lego",  # a short word with a letter more
        "take three of them",  # a number word
        'say "helo everyone" to Bob',  # quoted words are said as they are
        "hand me the jat",  # as close to the hat as to the mat: ambiguous
        "hand the lamb to Lanb",  # a capital mid-sentence: a name, written as meant
    ],
)
def test_correct_unknown_and_ambiguous_words_are_left_alone(text: str) -> None:
    spelled = corrected(text, lexicon_of(_things("lamb", "leg", "tree", "hat", "mat")))
    assert (spelled.text, spelled.corrections) == (text, ())


def test_names_follow_the_kb() -> None:
    kb = _things("ledge")
    assert corrected("pick up the thremos", lexicon_of(kb)).corrections == ()
    kb.update(["t9 rdf:type Artifact", 't9 rdfs:label "thermos"', "myself sees t9"])
    assert corrected("pick up the thremos", lexicon_of(kb)).text == "pick up the thermos"


def test_a_corrected_turn_is_less_sure_and_a_corrected_name_is_a_guess() -> None:
    kb = _things("thermos")
    plain = say(kb, "pick up the thermos")
    grammar = say(kb, "plaese pick up the thermos")
    name = say(kb, "pick up the thremos")
    assert plain.roles == grammar.roles == name.roles == {"object": "t0"}
    assert plain.confidence > grammar.confidence and name.confidence == grammar.confidence
    assert (plain.guessed, grammar.guessed, name.guessed) == (False, False, True)


def test_a_compound_request_with_a_slip_is_less_sure_in_every_part() -> None:
    out = say(_things("thermos", "ledge"), "tkae the thermos and put it on the ldege")
    assert [o.intent for o in out.steps()] == [I.GRAB_OBJECT, I.PLACE_OBJECT]
    assert all(o.confidence < 0.9 for o in out.steps()) and out.guesses


@pytest.mark.parametrize(
    ("text", "fixed"),
    [
        ("walk too the gate", "walk to the gate"),
        ("bring the milk form the fridge", "bring the milk from the fridge"),
        ("go two my room", "go to my room"),
        ("were is the gate", "where is the gate"),  # "were" before "is" at the start
    ],
)
def test_a_preposition_heard_as_another_word_before_a_noun_phrase(text: str, fixed: str) -> None:
    spelled = corrected(text, lexicon_of(_things("gate", "fridge")))
    assert spelled.text == fixed and not spelled.guessed


@pytest.mark.parametrize(
    "text", ["fill in the form the nurse gave you", "take two apples", "me too", "were the apples ripe"]
)
def test_the_same_words_elsewhere_are_left_alone(text: str) -> None:
    assert corrected(text, lexicon_of(_things("form", "apple"))).text == text


def test_a_preposition_typed_as_a_digit_before_a_persons_name() -> None:
    kb = scene_kb(None, "person_ola rdf:type Human", 'person_ola rdfs:label "Ola"',
                  "cup_1 rdf:type dbr:Cup", "myself sees cup_1")  # fmt: skip
    assert corrected("take the cup 2 ola", lexicon_of(kb)).text == "take the cup to ola"
    assert corrected("take 2 cups to ola", lexicon_of(kb)).text == "take 2 cups to ola"  # a number


def _diner() -> KB:
    return scene_kb(
        None,
        "person_nadia rdf:type Human", 'person_nadia rdfs:label "Nadia"', "myself sees person_nadia",
        "person_lee rdf:type Human", 'person_lee rdfs:label "Dr Lee"', "myself sees person_lee",
        "table_3 rdf:type dbr:Table_(furniture)", 'table_3 rdfs:label "table 3"', "myself sees table_3",
        "screen_2 rdf:type Artifact", 'screen_2 rdfs:label "screen 2"', "myself sees screen_2",
        "pie_1 rdf:type Artifact", 'pie_1 rdfs:label "apple pie"', "myself sees pie_1",
        "napkins_1 rdf:type Artifact", 'napkins_1 rdfs:label "pack of napkins"', "myself sees napkins_1",
        "straws_1 rdf:type Artifact", 'straws_1 rdfs:label "pack of straws"', "myself sees straws_1",
    )  # fmt: skip


@pytest.mark.parametrize(
    ("text", "fixed"),
    [
        # "for" heard as "four", before the speaker, a person or a noun phrase
        ("could you fetch the pie four me", "could you fetch the pie for me"),
        ("fetch the pie 4 nadia", "fetch the pie for nadia"),
        ("fetch the pie four dr lee", "fetch the pie for dr lee"),
        ("carry it two him", "carry it to him"),
        # "to" heard as "two" before a name of the KB said without its article
        ("carry the pie two table three", "carry the pie to table three"),
        ("carry it too table 3", "carry it to table 3"),
    ],
)
def test_a_preposition_heard_as_a_number_before_whom_or_where(text: str, fixed: str) -> None:
    spelled = corrected(text, lexicon_of(_diner()))
    assert spelled.text == fixed and not spelled.guessed


@pytest.mark.parametrize(
    "text",
    [
        "carry two pies to table three",  # a count: a plural follows
        "put the four pies on table 3",  # after a determiner
        "take me to screen 2 my film starts soon",  # the number of a name
        "go from screen two table three",
        "bring me four napkins",
    ],
)
def test_a_real_number_is_never_read_as_a_preposition(text: str) -> None:
    assert corrected(text, lexicon_of(_diner())).text == text


def test_a_slip_in_a_plural_is_corrected_to_the_plural() -> None:
    # the KB's names are indexed singular ("napkin"): "napkns" is two edits from it, one from "napkins"
    spelled = corrected("pls bring me a pack of napkns", lexicon_of(_diner()))
    assert spelled.text == "pls bring me a pack of napkins" and spelled.guessed
    out = say(_diner(), "pls bring me a pack of napkns", speaker="person_nadia")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "napkins_1", "recipient": "person_nadia"})


@pytest.mark.parametrize(
    ("text", "fixed"),
    [
        ("goto the shed", "go to the shed"),  # two grammar words typed as one
        ("put it infront of the shed", "put it in front of the shed"),
        ("someones left it here", "someone left it here"),  # someone's: never "some ones"
        ("show him through two the shed", "show him through to the shed"),  # a preposition after a particle
        ("hand me the pear of gloves", "hand me the pair of gloves"),  # homophones of the grammar's words
        ("go to the shed write now", "go to the shed right now"),
        ("wait their for the van", "wait there for the van"),
        ("bring their gloves", "bring their gloves"),  # a possessive before its noun stays
    ],
)
def test_run_together_words_and_homophones_of_grammar_words(text: str, fixed: str) -> None:
    kb = _things("shed", "gloves")
    assert corrected(text, lexicon_of(kb)).text == fixed
    kb.close()


def test_a_homophone_the_kb_names_is_never_read_otherwise() -> None:
    kb = _things("pear", "basket")
    assert corrected("bring me the pear of the basket", lexicon_of(kb)).text == "bring me the pear of the basket"
    kb.close()


def test_a_word_heard_for_the_one_name_that_sounds_the_same_is_that_name() -> None:
    kb = _things("guitar picks", "studio lamp")
    fixed = corrected("bring me the guitar pics", lexicon_of(kb))
    assert fixed.text == "bring me the guitar picks" and fixed.guessed
    kb.close()
