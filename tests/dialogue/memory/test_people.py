"""Each person's memory across dialogues: when they last spoke, a bounded summary, in the KB."""

from __future__ import annotations

import asyncio
from pathlib import Path

from rdflib import Literal

from dialogue import intents as I
from dialogue.engine import DialogueEngine, TurnResult
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.testing import ScriptedModel
from dialogue.memory.claims import Claim
from dialogue.memory.people import MAX_NOTES, MAX_SUMMARY, People, Recollection, note, summarised
from dialogue.memory.recollections import SUMMARY
from dialogue.sessions.manager import DialogueManager
from dialogue.sessions.observers import TurnRecord
from kb import KB
from kb.journal import Journal
from kb.terms import format_term

BOB = "person_bob"
T0 = 1_748_773_800.0  # 2025-06-01T10:30:00Z


def record(text: str, result: TurnResult, at: float = T0, user: str = BOB) -> TurnRecord:
    return TurnRecord("default", user, text, result, at)


BRING = I.make_intent(I.BRING_OBJECT, {"object": "mug_red", "recipient": BOB}, source=BOB, confidence=0.9)
TOLD = TurnResult("OK, the mug is yours.", claims=(Claim("mug_red", "belongsTo", BOB),))
CHAT = TurnResult("I'm fine, thank you!")


def test_a_turn_notes_what_was_told_or_asked_for_and_nothing_else() -> None:
    assert note(record("the red mug is mine", TOLD)) == '2025-06-01: said "the red mug is mine"'
    assert note(record("bring me my mug", TurnResult("OK.", (BRING,)))) == '2025-06-01: asked "bring me my mug"'
    assert note(record("how are you?", CHAT)) is None
    asked = TurnResult("Alice likes tea.", claims=(Claim("person_alice", "likes", None),))
    assert note(record("what does Alice like?", asked)) is None
    raw = I.raw_user_input("hmm", source=BOB)
    assert note(record("hmm", TurnResult("Sorry.", (raw,)))) is None
    # A greeting asks the robot to do nothing: "Hi, I'm Bob" is what Bob said, "hello" nothing notable.
    hello = I.make_intent(I.GREET, {"recipient": BOB}, source=BOB, confidence=0.9)
    named = TurnResult("Hello! Nice to meet you, Bob.", (hello,), claims=(Claim(BOB, "name", "Bob", "text"),))
    assert note(record("Hi, I'm Bob", named)) == '2025-06-01: said "Hi, I\'m Bob"'
    assert note(record("hello", TurnResult("Hello Bob!", (hello,)))) is None


def test_a_note_leaves_out_what_the_kb_cannot_keep() -> None:
    # issue 26, item 12: the KB refuses C0 controls (RDF/XML cannot carry them); said words keep the rest
    said = note(record("bring\x00 me\x1b[0m my mug\x07", TurnResult("OK.", (BRING,))))
    assert said == '2025-06-01: asked "bring me[0m my mug"'
    with KB() as kb:
        kb.add([f"{BOB} {format_term(SUMMARY)} {format_term(Literal(said))}"])  # accepted


def test_the_summary_keeps_the_latest_notes_within_its_bounds() -> None:
    summary = ""
    for n in range(MAX_NOTES + 3):
        summary = summarised(summary, f'2025-06-01: said "{n}"')
    assert summary.split("; ") == [f'2025-06-01: said "{n}"' for n in range(3, MAX_NOTES + 3)]
    long = summarised(summary, "x" * 500)
    assert len(long) <= MAX_SUMMARY and long.endswith("x" * 500)


def test_last_spoke_and_summary_are_facts_of_the_robots_model(home: KB) -> None:
    people = People(home, refresh=60)
    assert people.recall(BOB).last_spoke is None and asyncio.run(people.recall_note(BOB)) is None
    assert people.remember(record("the red mug is mine", TOLD))  # what was told: written at once
    assert home.find([f"{BOB} lastSpokeAt ?t"]) == [{"t": "2025-06-01T10:30:00+00:00"}]
    assert people.recall(BOB).summary == '2025-06-01: said "the red mug is mine"'
    # Requests and chit-chat write at most once per refresh period; their notes wait for it.
    assert not people.remember(record("bring me my mug", TurnResult("OK.", (BRING,)), at=T0 + 5))
    assert not people.remember(record("how are you?", CHAT, at=T0 + 30))
    assert people.recall(BOB).summary == '2025-06-01: said "the red mug is mine"'
    assert people.remember(record("how are you?", CHAT, at=T0 + 65))
    memory = people.recall(BOB)
    assert memory.last_spoke == "2025-06-01T10:31:05+00:00"
    assert memory.summary == '2025-06-01: said "the red mug is mine"; 2025-06-01: asked "bring me my mug"'
    assert asyncio.run(people.recall_note(BOB)) == (
        f"You last spoke with [{BOB}] on 2025-06-01 at 10:31 UTC. Earlier: {memory.summary}.")
    # Nobody to remember: ROS4HRI's source constants; a turn the service could not answer.
    assert not people.remember(record("hello", CHAT, user=I.UNKNOWN_AGENT))
    assert not people.remember(record("x", TurnResult("Sorry.", error_msg="model down"), at=T0 + 999))


def test_a_clean_stop_writes_what_was_waiting_for_the_next_write(home: KB) -> None:
    people = People(home, refresh=60)
    people.remember(record("the red mug is mine", TOLD))
    assert not people.remember(record("bring me my mug", TurnResult("OK.", (BRING,)), at=T0 + 5))
    assert not people.remember(record("how are you?", CHAT, at=T0 + 10))
    people.close()  # the service stops within the refresh period: nothing of it is lost
    memory = People(home).recall(BOB)
    assert memory.last_spoke == "2025-06-01T10:30:10+00:00"
    assert memory.summary == '2025-06-01: said "the red mug is mine"; 2025-06-01: asked "bring me my mug"'


def test_the_memory_survives_a_restart_with_the_journal(tmp_path: Path, home: KB) -> None:
    kb = KB()
    journal = Journal(tmp_path)
    journal.recover(kb)
    People(kb).remember(record("the red mug is mine", TOLD))
    journal.close()
    kb.close()
    again = KB()
    Journal(tmp_path).recover(again)
    assert People(again).recall(BOB).summary == '2025-06-01: said "the red mug is mine"'


def test_the_dialogue_manager_keeps_it_and_gives_a_model_the_note(home: KB) -> None:
    model = ScriptedModel([{"verbal_ack": "Hi!", "user_intent": None}] * 2)
    people = People(home)
    engine = DialogueEngine(home, HybridModel(model))
    manager = DialogueManager(engine, observers=[people.observe], recall=people.recall_note)

    async def run() -> None:
        await manager.interact(BOB, "my name is Bob")  # the rules learn it: no model asked
        await manager.interact(BOB, "hello there, how is life?")

    asyncio.run(run())
    assert model.requests and "my name is Bob" in people.recall(BOB).summary
    notes = [m.content for m in model.requests[0].messages if m.role == "system"]
    assert any(n.startswith(f"You last spoke with [{BOB}]") for n in notes)
    stored = asyncio.run(manager.get_async("default")).history
    assert all(u.speaker != "__system__" for u in stored)  # the note is for the model, not the history


def test_the_index_follows_every_change_so_recalling_needs_no_query(home: KB) -> None:
    home.update([f'{BOB} lastSpokeAt "2025-05-01T09:00:00+00:00"^^xsd:dateTime'])
    people = People(home)
    people.follow()
    assert people.recall(BOB).last_spoke == "2025-05-01T09:00:00+00:00"
    People(home).remember(record("the red mug is mine", TOLD))  # another writer of the same KB
    assert people.recall(BOB) == Recollection(BOB, "2025-06-01T10:30:00+00:00",
                                              '2025-06-01: said "the red mug is mine"')
    home.remove([f"{BOB} dialogueSummary ?s"])
    assert people.recall(BOB).summary == ""
    home.clear()
    assert people.recall(BOB) == Recollection(BOB)
    note = asyncio.run(people.recall_note(BOB))
    assert note is None
    people.close()
