"""English is the language folder's (issue 28): the packages that read words hold none in their
Python, and the rest of the offline understanding holds a budget of word tables that only shrinks.
What counts as English in code is `tests.englishcode`'s (its docstring says)."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

from tests.englishcode import Finding, findings

#: Modules whose English words are all in `lang/<code>/`.
CLEAN = (
    "dialogue/reference/",
    "dialogue/memory/",
    "dialogue/ask/",
    "dialogue/validate.py",
    "dialogue/understanding/followups/correction.py",
    "dialogue/understanding/followups/request.py",
    "dialogue/understanding/followups/statement.py",
    "dialogue/understanding/questions/answers.py",
    "dialogue/understanding/questions/grammar.py",
    "dialogue/understanding/questions/told.py",
    "dialogue/understanding/questions/vocabulary.py",
    "dialogue/understanding/requests/adjuncts.py",
    "dialogue/understanding/requests/commands.py",
    "dialogue/understanding/requests/constructions.py",
    "dialogue/understanding/requests/needs.py",
    "dialogue/understanding/requests/ground.py",
    "dialogue/understanding/requests/phrase.py",
    "dialogue/understanding/requests/referents.py",
    "dialogue/understanding/requests/telling.py",
    "dialogue/understanding/requests/terse.py",
    "dialogue/understanding/requests/timing.py",
    "dialogue/understanding/speech/clauses.py",
    "dialogue/understanding/speech/plain.py",
    "dialogue/understanding/speech/repair.py",
    "dialogue/understanding/statements/clause.py",
    "dialogue/understanding/statements/grammar.py",
    "dialogue/understanding/statements/likings.py",
)
#: What the scanner takes for words there and is the code's own names, with why.
NAMES = {
    ("dialogue/ask/form.py", "question, required"): "the configuration's JSON keys",
    ("dialogue/ask/model.py", "answers, cancel"): "the answer schema's JSON keys",
    ("dialogue/ask/model.py", "situation, input, filled, missing"): "the prompt template's slots",
    ("dialogue/ask/model.py", "minimum, maximum, pattern"): "JSON-schema keywords",
    ("dialogue/memory/claims.py", "likes, dislikes"): "the KB's properties",
    ("dialogue/memory/learn.py", "adopted, known, believed, perceived, disputed, unknown ..."): "outcomes",
    ("dialogue/memory/learn.py", "add, remove"): "a batch's operations",
    ("dialogue/memory/people.py", "person, summary, told"): "a note's JSON keys",
    ("dialogue/memory/replies.py", "adopted, known, believed"): "outcomes",
    ("dialogue/memory/replies.py", "likes, dislikes"): "the KB's properties",
    ("dialogue/reference/facts.py", "support, zone, colour, owner, engagement, movable"): "snapshot tables",
    # The snapshot's relations are named by the phrase the preposition table's `relations` column
    # refers to them by: a key shared by the KB's side and the language's, not words heard.
    ("dialogue/reference/facts.py", "next to, near, under, above, behind, behind ..."): "relation keys",
    ("dialogue/reference/facts.py", "above, behind, near, under"): "relation keys",
    ("dialogue/reference/lexicon.py", "norm, phrase, singular"): "__all__",
    ("dialogue/reference/lexicon.py", "synonym, kind"): "name sources",
    ("dialogue/reference/naming.py", "synonym, kind"): "name sources",
}
#: Word tables still in the rest of the offline understanding, per module: lower a figure whenever
#: one moves to the language folder; a module not listed may hold none.
BUDGET = {
    "dialogue/understanding/questions/situation.py": 2,
    "dialogue/understanding/requests/frames.py": 2,
    "dialogue/understanding/speech/spelling.py": 2,
}
#: What the scanner takes for a compared word in a CLEAN module and is the code's own name, with why.
COMPARED_NAMES = {
    ("dialogue/memory/learn.py", "known"): "a claim's outcome",
    ("dialogue/memory/learn.py", "answered"): "a claim's outcome",
    ("dialogue/memory/replies.py", "known"): "a claim's outcome",
    ("dialogue/reference/entities.py", "in"): "a relation key (`facts.RELATIONS`)",
    ("dialogue/reference/headnoun.py", "in"): "a relation key (`facts.RELATIONS`)",
    ("dialogue/reference/resolution.py", "in"): "a relation key (`facts.RELATIONS`)",
    ("dialogue/reference/facts.py", "sees"): "the KB's property",
    ("dialogue/understanding/followups/correction.py", "rest"): "a slot's name",
    ("dialogue/understanding/requests/commands.py", "extra"): "a slot's name",
    ("dialogue/understanding/questions/grammar.py", "x"): "a placeholder word the code puts in itself",
}
#: Words still compared in the Python of CLEAN modules (`w == "of"`, `"not" in w`), per module: lower
#: a figure whenever one moves to the language folder; a CLEAN module not listed may compare none.
COMPARED = {
    "dialogue/reference/headnoun.py": 2,
    "dialogue/reference/resolution.py": 3,
    "dialogue/reference/unnamed.py": 2,
    "dialogue/understanding/followups/correction.py": 5,
    "dialogue/understanding/followups/request.py": 5,
    "dialogue/understanding/questions/answers.py": 1,
    "dialogue/understanding/questions/grammar.py": 22,
    "dialogue/understanding/questions/told.py": 5,
    "dialogue/understanding/requests/adjuncts.py": 1,
    "dialogue/understanding/requests/commands.py": 12,
    "dialogue/understanding/requests/constructions.py": 10,
    "dialogue/understanding/requests/needs.py": 2,
    "dialogue/understanding/requests/phrase.py": 5,
    "dialogue/understanding/requests/referents.py": 2,
    "dialogue/understanding/requests/telling.py": 14,
    "dialogue/understanding/requests/timing.py": 2,
    "dialogue/understanding/speech/clauses.py": 5,
    "dialogue/understanding/speech/plain.py": 7,
    "dialogue/understanding/speech/repair.py": 1,
    "dialogue/understanding/statements/grammar.py": 6,
    "dialogue/understanding/statements/likings.py": 2,
}
#: Sentences still written in Python outside the reply templates, per module, with why.
SENTENCES = {
    "dialogue/situation.py": 4,  # the model's prompt, not a reply (prompts/ holds its templates)
    "dialogue/llm/llamabuild.py": 1,  # a probe message to a model being built
}


@pytest.fixture(scope="module")
def found() -> list[Finding]:
    return findings()


def test_the_packages_that_read_words_hold_no_english_in_python(found: list[Finding]) -> None:
    english = [
        str(f)
        for f in found
        if f.path.startswith(CLEAN)
        and f.kind in ("word table", "spatial table", "english regex")
        and (f.path, f.text) not in NAMES
    ]
    assert not english, "\n".join(english)


def test_the_clean_packages_compare_no_more_words_than_they_did(found: list[Finding]) -> None:
    compared = Counter(
        f.path
        for f in found
        if f.kind == "compared word" and f.path.startswith(CLEAN) and (f.path, f.text) not in COMPARED_NAMES
    )
    over = {path: n for path, n in compared.items() if n > COMPARED.get(path, 0)}
    assert not over, over


def test_a_compared_word_is_found(tmp_path: Path) -> None:
    (tmp_path / "dialogue").mkdir()
    (tmp_path / "dialogue" / "x.py").write_text(
        "from typing import Literal\n"
        'Kind = Literal["person"]\n'
        "def f(w: tuple[str, ...], k: Kind) -> bool:\n"
        '    return w[0] != "not" and "of" in w and w[:1] == ("the",) and k == "person" and w[0] == "?"\n'
    )
    assert sorted(f.text for f in findings(tmp_path) if f.kind == "compared word") == ["not", "of", "the"]


def test_the_rest_of_the_understanding_keeps_within_its_budget_of_word_tables(found: list[Finding]) -> None:
    tables = Counter(
        f.path
        for f in found
        if f.kind == "word table"
        and f.path.startswith("dialogue/understanding/")
        and not f.path.startswith(CLEAN)
    )
    over = {path: n for path, n in tables.items() if n > BUDGET.get(path, 0)}
    assert not over, over


def test_replies_are_the_templates_of_the_language(found: list[Finding]) -> None:
    sentences = Counter(f.path for f in found if f.kind == "reply sentence")
    over = {path: n for path, n in sentences.items() if n > SENTENCES.get(path, 0)}
    assert not over, over


def test_english_in_code_is_found(tmp_path: Path) -> None:
    """What the scanner must find, it finds (a test that cannot fail is no test)."""
    (tmp_path / "dialogue").mkdir()
    (tmp_path / "dialogue" / "x.py").write_text(
        'W = frozenset({"on", "under"})\n'
        "def f(w: str) -> str:\n"
        '    return "Sorry, I cannot." if w in ("please", "thanks") else f"I see {w} there."\n'
    )
    kinds = Counter(f.kind for f in findings(tmp_path))
    assert kinds == {"word table": 2, "spatial table": 1, "reply sentence": 2}


def test_no_stage_of_the_understanding_re_tokenises(found: list[Finding]) -> None:
    """Every stage reads the utterance object (dialogue.understanding.said), not its text again."""
    assert not [str(f) for f in found if f.kind == "re-tokenisation"]


def test_a_stage_cutting_a_text_again_is_found(tmp_path: Path) -> None:
    stage = tmp_path / "dialogue" / "understanding"
    stage.mkdir(parents=True)
    (stage / "x.py").write_text("import re\ndef f(text: str) -> list[str]:\n    return text.split() + re.findall('a', text)\n")
    assert Counter(f.kind for f in findings(tmp_path)) == {"re-tokenisation": 2}


def test_literal_values_imported_from_another_module_are_the_codes_names(tmp_path: Path) -> None:
    (tmp_path / "dialogue").mkdir()
    (tmp_path / "dialogue" / "kinds.py").write_text(
        'from typing import Literal\nAct = Literal["greeting", "thanks"]\nclass Parse:\n    act: Act\n'
    )
    (tmp_path / "dialogue" / "x.py").write_text(
        "from dialogue.kinds import Parse\n"
        'A = frozenset({"greeting", "thanks"})\n'
        'B = frozenset({"greeting", "cheers"})\n'
    )
    assert [f.line for f in findings(tmp_path) if f.path == "dialogue/x.py"] == [3]


def test_no_regex_of_dialogue_spells_english(found: list[Finding]) -> None:
    """A pattern of words is the language folder's; the regexes left read machine text."""
    assert not [str(f) for f in found if f.kind == "english regex"]
