"""A language folder read as tables: English's closed-class words (numbers written the other way),
its one preposition table, and clear errors for a folder that is not a language's."""

from pathlib import Path

import pytest

from dialogue import intents as I
from dialogue.reference.grounding import build_snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.language import Language, LanguageError
from tests.dialogue.conftest import english, scene_kb


def other_numbers(words: list[str]) -> tuple[str, ...] | None:
    return english().words.other_numbers(words)


@pytest.mark.parametrize(
    ("words", "other"),
    [
        ("bay 4", ("bay", "four")),
        ("bay four", ("bay", "4")),
        ("gate 21", ("gate", "twenty", "one")),
        ("gate twenty one", ("gate", "21")),
        ("room 40 b", ("room", "forty", "b")),
        ("row zero", ("row", "0")),
    ],
)
def test_a_number_in_digits_is_said_in_words_and_back(words: str, other: tuple[str, ...]) -> None:
    assert other_numbers(words.split()) == other


def test_words_without_a_number_have_no_other_form() -> None:
    assert other_numbers(["the", "red", "mug"]) is None
    assert other_numbers(["room", "101"]) is None  # only numbers below a hundred are said


def test_english_is_read_from_its_folder() -> None:
    lang = english()
    assert lang.code == "en" and "the" in lang.words.determiners and "on" in lang.support
    assert lang.prepositions.longest_first("place")[0] == ("on", "top", "of")
    assert lang.prepositions.row(["next", "to"]) is not None and "= " in lang.lexicon


def test_a_file_that_is_not_the_languages_is_refused_with_its_name(tmp_path: Path) -> None:
    (tmp_path / "words.toml").write_text('determiners = "the"\nnouns = "cup"\n')
    with pytest.raises(LanguageError, match=r"words\.toml.*nouns"):
        Language.read(tmp_path)
    (tmp_path / "words.toml").write_text("determiners = [\n")
    with pytest.raises(LanguageError, match=r"words\.toml"):
        Language.read(tmp_path)
    with pytest.raises(LanguageError, match="no language folder"):
        Language.read(tmp_path / "xx")


def test_what_a_language_leaves_out_is_empty(tmp_path: Path) -> None:
    (tmp_path / "words.toml").write_text('determiners = "de het een"\n')
    lang = Language.read(tmp_path, "nl")
    assert lang.code == "nl" and lang.words.determiners == {"de", "het", "een"}
    assert lang.words.colours == frozenset() and lang.support == frozenset() and lang.lexicon == ""


#: A tiny second language, as a folder of its own: a few words, one frame, a few replies.
DUTCH = Path(__file__).parent / "lang" / "nl"


def test_a_second_language_folder_reads_a_request_in_it() -> None:
    """Adding a language is adding a folder: the same grammar reads a request in Dutch from a
    folder of the tests, and says it back in Dutch."""
    dutch = Language.read(DUTCH)
    kb = scene_kb(None, 'cup_1 rdf:type dbr:Cup', 'cup_1 rdfs:label "beker"', "myself sees cup_1",
                  "person_ana rdf:type Human", 'person_ana rdfs:label "Ana"', "myself sees person_ana")
    lexicon = Lexicon(build_snapshot(kb), dutch)
    out = Interpreter(lexicon, "person_bob").interpret("breng de beker naar Ana")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "cup_1", "recipient": "person_ana"})
    assert out.reply == "Goed, ik breng de beker naar Ana."
    # English is not what this folder says
    english_said = Interpreter(lexicon, "person_bob").interpret("bring the cup to Ana")
    assert english_said.intent is None and english_said.reply == "Sorry, dat begreep ik niet."
    # and the same request is English's own in English
    said = Interpreter(Lexicon(build_snapshot(kb), english()), "person_bob").interpret("bring the beker to Ana")
    assert (said.intent, said.roles) == (I.BRING_OBJECT, {"object": "cup_1", "recipient": "person_ana"})
    kb.close()
