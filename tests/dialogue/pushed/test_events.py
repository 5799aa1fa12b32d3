"""A pushed intent's shapes: an emitted one (not numbered yet) from a turn, and its JSON."""

from __future__ import annotations

from dialogue import intents as I
from dialogue.engine import TurnResult
from dialogue.pushed.events import Emitted, emitted
from dialogue.sessions.observers import TurnRecord


def test_a_turns_intents_are_emitted_in_order_with_the_reply_on_the_first_and_the_turns_time() -> None:
    greet = I.make_intent(I.GREET, {"recipient": "person_ann"}, source="person_ann", confidence=1.0)
    move = I.make_intent(I.MOVE_TO, {"goal": "kitchen"}, source="person_ann", confidence=0.9)
    record = TurnRecord("hall", "person_ann", "hi, go to the kitchen", TurnResult("Hello! OK.", (greet, move)), 12.5)
    assert emitted(record) == [Emitted("dialogue", greet, "hall", "Hello! OK.", 12.5),
                               Emitted("dialogue", move, "hall", "", 12.5)]
    assert emitted(record)[0].as_json() == {"time": 12.5, "origin": "dialogue", "dialogue_id": "hall",
                                            "response": "Hello! OK.", "intent": greet.model_dump(mode="json")}
    assert emitted(TurnRecord("hall", "person_ann", "what?", TurnResult("Sorry?"), 13.0)) == []
