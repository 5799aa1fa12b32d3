"""The words the grammar of questions reads, gathered once per language."""

from dialogue.understanding.questions.vocabulary import QuestionWords
from tests.dialogue.conftest import english


def test_the_words_are_gathered_once_per_language() -> None:
    lang = english()
    assert lang.derived(QuestionWords) is lang.derived(QuestionWords)


def test_they_are_the_language_s_own() -> None:
    q = english().derived(QuestionWords)
    situation = english().questions.situation
    assert q.sees.table == situation.sees and q.describe.table == situation.describe
    assert q.locatives == english().prepositions.having("asked-on")
