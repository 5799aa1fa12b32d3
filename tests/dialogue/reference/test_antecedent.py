
from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.reference import antecedent as antecedents
from dialogue.reference.antecedent import antecedent
from dialogue.reference.grounding import Kind
from dialogue.reference.resolution import ANYWHERE
from kb import KB
from tests.dialogue.conftest import english, lexicon_of, scene_kb


def pronoun_kinds(words: list[str], kinds: frozenset[Kind]) -> frozenset[Kind]:
    return antecedents.pronoun_kinds(english(), words, kinds)

THING: frozenset[Kind] = frozenset({"thing"})
PERSON: frozenset[Kind] = frozenset({"person"})


def test_pronoun_antecedent_skips_locative_mentions(kitchen: KB) -> None:
    lex = lexicon_of(kitchen)
    found = antecedent(lex, ["do you see a book?", "Yes, I see a cookbook on the shelf."], THING)
    assert found is not None and found.id == "book_1"
    assert antecedent(lex, ["hello"], THING) is None


def test_pronoun_kinds_her_is_a_person_it_never_is() -> None:
    assert pronoun_kinds(["her"], ANYWHERE) == PERSON
    assert pronoun_kinds(["him"], THING) == frozenset()
    assert pronoun_kinds(["it"], ANYWHERE) == ANYWHERE - PERSON
    assert pronoun_kinds(["them"], ANYWHERE) == ANYWHERE


def test_an_antecedent_said_with_whose_it_is_is_that_persons() -> None:
    kb = scene_kb(None, "p_1 rdf:type Human", 'p_1 rdfs:label "Noor"', "myself sees p_1",
                  "p_2 rdf:type Human", 'p_2 rdfs:label "Sam"', "myself sees p_2",
                  "k_1 rdf:type Artifact", 'k_1 rdfs:label "key"', "k_1 belongsTo p_1", "myself sees k_1",
                  "k_2 rdf:type Artifact", 'k_2 rdfs:label "key"', "k_2 belongsTo p_2", "myself sees k_2")  # fmt: skip
    lex = lexicon_of(kb)
    robot = Utterance(ASSISTANT_USER_ID, "Your key is by the door.")
    assert antecedent(lex, [robot], THING, speaker="p_2").id == "k_2"  # type: ignore[union-attr]
    assert antecedent(lex, [Utterance("p_1", "i lost my key")], THING).id == "k_1"  # type: ignore[union-attr]
    assert antecedent(lex, ["sams key is missing"], THING).id == "k_2"  # type: ignore[union-attr]
    assert antecedent(lex, ["the key is missing"], THING) is None  # two keys, nothing says whose


def test_a_things_pronoun_is_never_where_the_turn_put_something() -> None:
    kb = scene_kb(None, "t_1 rdf:type Artifact", 't_1 rdfs:label "counter"', "myself sees t_1",
                  "p_1 rdf:type Human", 'p_1 rdfs:label "Noor"', "myself sees p_1")  # fmt: skip
    lex = lexicon_of(kb)
    assert antecedent(lex, ["my spoons are on the counter"], THING) is None
    assert antecedent(lex, ["my spoons are on the counter"], THING, place=True).id == "t_1"  # type: ignore[union-attr]
    assert antecedent(lex, ["give the spoon to noor"], PERSON).id == "p_1"  # type: ignore[union-attr]
