"""With more visible things than the prompt holds, the turn keeps what matters (issue 18)."""

from __future__ import annotations

import asyncio
from collections.abc import Sequence

from dialogue.engine import DialogueEngine
from dialogue.reference.english import tokens
from dialogue.reference.grounding import Entity, build_snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.relevance import Focus, mentioned, ranked
from kb import KB
from tests.dialogue.conftest import english

ALICE = "person_alice"


def crowded(objects: int = 500) -> KB:
    """A robot that sees `objects` cups (ids sort before the speaker and the furniture)."""
    kb = KB()
    kb.update([
        "myself rdf:type Robot", "kitchen rdf:type ZoneOfInterest", 'kitchen rdfs:label "kitchen"',
        f"{ALICE} rdf:type Human", f'{ALICE} rdfs:label "Alice"', f"myself sees {ALICE}",
        "shelf_1 rdf:type dbr:Shelf_(storage)", "shelf_1 isIn kitchen",
        "apple_1 rdf:type dbr:Apple", "apple_1 isIn kitchen", "zz_jar rdf:type Jar", "zz_jar isIn kitchen",
        *(s for i in range(objects) for s in (f"a_cup_{i:04d} rdf:type dbr:Cup", f"myself sees a_cup_{i:04d}",
                                              f"a_cup_{i:04d} isIn kitchen")),
    ])  # fmt: skip
    return kb


def test_500_visible_objects_hello_greets_the_speaker_by_name() -> None:
    engine = DialogueEngine(crowded())
    result = asyncio.run(engine.turn("hello", speaker=ALICE))
    assert "Alice" in result.response


def test_500_visible_objects_put_the_apple_on_the_shelf_grounds() -> None:
    engine = DialogueEngine(crowded())
    result = asyncio.run(engine.turn("put the apple on the shelf", speaker=ALICE))
    assert result.backend == "rules" and not result.error_msg, result
    roles = result.intents[0].data
    assert roles["object"] == "apple_1" and roles["recipient"] == "shelf_1"


def test_the_speaker_people_present_and_mentioned_things_come_first() -> None:
    kb = crowded()
    snapshot = build_snapshot(kb)
    named = mentioned(Lexicon(snapshot, english()), tokens("put the apple on the shelf"))
    assert sorted(named) == ["apple_1", "shelf_1"]
    kept = [e.id for e in ranked(snapshot, ALICE, 10, named)]
    assert kept[:2] == [ALICE, "myself"]
    assert kept[2:4] == ["apple_1", "shelf_1"]  # before 500 visible cups sorted before them by id
    assert len(kept) == 10 and all(k.startswith("a_cup_") for k in kept[4:])


def test_places_of_kept_things_are_kept_too() -> None:
    snapshot = build_snapshot(crowded(3))
    kept = [e.id for e in ranked(snapshot, ALICE, 7, ["apple_1"])]
    assert kept == [ALICE, "myself", "apple_1", "a_cup_0000", "a_cup_0001", "a_cup_0002", "kitchen"]


def test_the_schema_enums_follow_the_ranking() -> None:
    engine = DialogueEngine(crowded())
    snapshot, lexicon = engine.ground()
    turn = engine.prepare((snapshot, lexicon), "bring me the apple", ALICE, (), None)
    schema = str(engine.schema_for(snapshot, ALICE, turn.context.focus))
    assert "apple_1" in schema
    assert "apple_1" not in str(engine.schema_for(snapshot, ALICE))  # 60 cups come first without the words


def test_the_rules_understand_entities_beyond_the_prompts_share() -> None:
    snapshot = build_snapshot(crowded())
    assert len(snapshot.entities) > 500 and "zz_jar" in snapshot.entities  # unseen, sorted last
    assert {e for m in Lexicon(snapshot, english()).mentions(["jar"]) for e in m.entities} == {"zz_jar"}


def test_the_focus_is_ranked_only_when_read_and_once() -> None:
    snapshot = build_snapshot(crowded(3))
    asked: list[str] = []
    told: list[Sequence[Entity]] = []

    def mentions() -> list[str]:
        asked.append("mentions")
        return ["apple_1"]

    focus = Focus(snapshot, ALICE, 7, mentions, then=told.append)
    assert asked == [] and told == []  # nothing done until read
    assert [e.id for e in focus] == [e.id for e in ranked(snapshot, ALICE, 7, ["apple_1"])]
    assert focus[0].id == ALICE and len(focus) == 7
    assert asked == ["mentions"] and len(told) == 1  # ranked once, and told once


def test_a_turn_the_rules_answer_ranks_nothing() -> None:
    engine = DialogueEngine(crowded())
    trace = asyncio.run(engine.turn("put the apple on the shelf", speaker=ALICE)).trace
    assert trace is not None and trace.answered_by == "rules"
    assert trace.snapshot is not None and trace.snapshot.entities > 500 and trace.snapshot.focus == []
