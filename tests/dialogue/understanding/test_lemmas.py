from types import MappingProxyType

import pytest
from lemminflect import getAllLemmas

from dialogue.understanding.lemmas import lemmas_of


@pytest.mark.parametrize("word", ["went", "cups", "Bob", "reading", "xqzt", "glasses", "left"])
def test_lemmas_are_lemminflects(word: str) -> None:
    assert dict(lemmas_of(word)) == getAllLemmas(word)


def test_an_unknown_word_has_none() -> None:
    assert not lemmas_of("xqztvb")


def test_a_words_lemmas_are_looked_up_once_and_cannot_be_changed() -> None:
    first = lemmas_of("carried")
    assert lemmas_of("carried") is first
    assert isinstance(first, MappingProxyType)
    with pytest.raises(TypeError):
        first["NOUN"] = ("carry",)  # type: ignore[index]
