"""The utterance object (dialogue.understanding.said): a turn's words are scanned by the one
tokeniser once, however many stages and readers read them."""

from __future__ import annotations

import asyncio
from collections import Counter
from decimal import Decimal

import pytest

import dialogue.reference.english as english
from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.reference.grounding import build_snapshot
from dialogue.understanding.readers import Turn, read
from dialogue.understanding.said import Said
from kb import KB
from tests.dialogue.conftest import english as language
from tests.dialogue.conftest import lexicon_of

BOB = "person_bob"

#: A turn for each reader and stage: requests (compound, self-repaired, clause by clause, spelled
#: out, mistyped, a message to pass on, a quote), a question about the situation, statements, a
#: question about what was told, a request with what a clause after it says of the thing, an answer
#: to the robot's question and a correction of the request just made.
TURNS: list[tuple[str, tuple[tuple[str, str], ...]]] = [
    ("Ari, would you pick up the stapler", ()),
    ("go to the desk and take the pear, then bring it to Carol", ()),
    ("bring me the uh no wait put the pear on the shelf", ()),
    ("The laptop. Pick it up.", ()),
    ("pick up the s t a p l e r", ()),
    ("pick up teh stapler", ()),
    ("tell Carol that dinner is ready please", ()),
    ("say 'stop and wait' to Carol", ()),
    ("where is the stapler?", ()),
    ("my name is Bob", ()),
    ("I like tea", ()),
    ("what does Carol like?", ()),
    ("take the pear, it is the one on the shelf", ()),
    ("the green one", (("assistant", "Which mug do you mean, the green mug or the red mug?"),)),
    ("sorry, I meant the shelf", (("user", "take the pear to the desk"), ("assistant", "OK, I will bring the pear to the desk."))),
]


@pytest.fixture
def scanned(monkeypatch: pytest.MonkeyPatch) -> Counter[str]:
    """Each text the one tokeniser scans, counted (`tokens` and `spans` lower the text they scan)."""
    seen: Counter[str] = Counter()
    lowered = english.lowered

    def counting(text: str) -> str:
        seen[text] += 1
        return lowered(text)

    monkeypatch.setattr(english, "lowered", counting)
    return seen


def kb_names(kb: KB) -> set[str]:
    """The ids and names of the KB's things: replies and grounding read those, not the turn."""
    return {name for e in build_snapshot(kb).entities.values()
            for name in (e.id, e.name, *e.labels, *e.class_names, e.colour) if name}  # fmt: skip


def test_a_text_of_the_turn_is_one_object_scanned_once(scanned: Counter[str]) -> None:
    said = Said(language(), "Take the cup, then the plate")
    part = said.of("then the plate")
    assert said.of("then the plate") is part and said.of(said.text) is said
    assert said.tokens == ("take", "the", "cup", "then", "the", "plate")
    assert [w for w, _, _ in said.marked] == ["take", "the", "cup", ",", "then", "the", "plate"]
    assert part.spans == (("then", 0, 4), ("the", 5, 8), ("plate", 9, 14))
    assert said.word("cup").tokens == ("cup",) and said.word("cup") is said.word("cup")
    assert scanned == Counter({"Take the cup, then the plate": 1, "then the plate": 1})


def test_a_form_of_the_words_is_made_once_per_text() -> None:
    made: list[str] = []

    def shout(said: Said) -> str:
        made.append(said.text)
        return said.text.upper()

    said = Said(language(), "hello there")
    assert (said.form(shout), said.form(shout), said.of("hello there").form(shout)) == ("HELLO THERE",) * 3
    assert made == ["hello there"]


def utterances(history: tuple[tuple[str, str], ...]) -> tuple[Utterance, ...]:
    return tuple(Utterance(BOB if who == "user" else ASSISTANT_USER_ID, said) for who, said in history)


@pytest.mark.parametrize(("text", "history"), TURNS)
def test_the_readers_scan_each_text_of_a_turn_once(
    office: KB, scanned: Counter[str], text: str, history: tuple[tuple[str, str], ...]
) -> None:
    lexicon = lexicon_of(office)
    names = kb_names(office)

    def turn() -> Turn:
        return Turn(Said(lexicon.lang, text), lexicon, BOB, utterances(history), "Ari")

    read(turn())  # (the language's own tables, the robot's name among them, are made once, on a first turn)
    scanned.clear()
    read(turn())
    assert scanned[text] == 1
    assert {said: n for said, n in scanned.items() if n > 1 and said not in names} == {}


@pytest.mark.parametrize(("text", "history"), TURNS)
def test_the_engine_and_the_rules_share_the_reading_of_a_turn(
    office: KB, scanned: Counter[str], text: str, history: tuple[tuple[str, str], ...]
) -> None:
    engine = DialogueEngine(office, config=EngineConfig(robot_name="Ari"))
    result = asyncio.run(engine.turn(text, speaker=BOB, history=list(utterances(history))))
    assert result.backend == "rules"
    assert scanned[text] == 1  # (what the turn names, for the prompt's share of the KB, and every reader)


def test_the_words_as_written_and_the_quotes_are_the_utterances() -> None:
    """What keeps the casing or the quotes reads it off the utterance, not off its text again."""
    said = Said(language(), 'say “Stop now” to  "Bob" O\'Brien')
    assert said.written == ("say", "“Stop", "now”", "to", '"Bob"', "O'Brien")
    assert said.unquoted == ("say", "Stop", "now", "to", "Bob", "O'Brien")
    assert [said.text[a:b] for a, b in said.quoted] == ["“Stop now”", '"Bob"']
    assert said.word("Bob").written == ("Bob",)


def test_the_ids_as_typed_and_the_numbers_said_are_the_utterances() -> None:
    said = Said(language(), "put cup_1 on dbr:Table_(furniture), minus three and a half, the red one")
    assert said.typed[:3] == ("put", "cup_1", "on") and "dbr:Table_(furniture)" in said.typed
    assert said.numbers == (Decimal("-3.5"),)
