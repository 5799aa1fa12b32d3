import pytest

from dialogue.reference import synonyms as packaged
from dialogue.reference.lexicon import phrase
from dialogue.reference.synonyms import Normaliser, SynonymError, Synonyms, parse
from tests.dialogue.conftest import english


def synonyms(normalise: Normaliser) -> Synonyms:
    """The packaged lexicon file's (English)."""
    return packaged.synonyms(english(), normalise)


def test_groups_and_kinds() -> None:
    syn = parse("# comment\nfridge = refrigerators\n\npaperback hardback < book  # kinds\n", phrase)
    assert syn.of(("refrigerator",)) == (("fridge",),) and syn.of(("fridge",)) == (("refrigerator",),)
    assert syn.kind_of(("paperback",)) == (("book",),) and syn.of(("book",)) == ()


@pytest.mark.parametrize("line", ["fridge", "a = ", "a < b < c", "a = b < c", " < book"])
def test_a_bad_line_is_refused_with_its_number(line: str) -> None:
    with pytest.raises(SynonymError, match="line 2"):
        parse(f"x = y\n{line}\n", phrase)


def test_the_packaged_file_parses() -> None:
    assert synonyms(phrase).of(("cellphone",))


def test_general_names_go_one_way_and_kinds_both() -> None:
    syn = parse("bag > satchel tote\nnovel < book\n", phrase)
    # "the bag" may be the satchel; "the satchel" is no other bag
    assert syn.broader_than(("satchel",)) == (("bag",),) and syn.kind_of(("satchel",)) == ()
    # a novel is a book, and "the novel" may be a thing the KB only calls a book
    assert syn.broader_than(("novel",)) == (("book",),) and syn.kind_of(("novel",)) == (("book",),)


@pytest.mark.parametrize("line", ["bag > ", "> satchel", "a < b > c", "a > b = c"])
def test_a_bad_general_name_line_is_refused(line: str) -> None:
    with pytest.raises(SynonymError, match="line 1"):
        parse(f"{line}\n", phrase)


def test_everyday_names_of_garden_and_care_things() -> None:
    syn = synonyms(phrase)
    # "the clippers" may be the secateurs, and "pruners" are secateurs; a zimmer is a walking frame
    assert phrase("clippers") in syn.broader_than(phrase("secateurs"))
    assert phrase("pruners") in syn.of(phrase("secateurs"))
    assert phrase("walking frame") in syn.of(phrase("zimmer frame"))
