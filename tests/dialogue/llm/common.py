from dialogue.llm.base import ChatMessage, ChatRequest, TurnContext
from dialogue.reference.grounding import Snapshot
from dialogue.schema import SchemaCandidates, turn_schema

SCHEMA = turn_schema(SchemaCandidates(["cup_1"], ["person_a"], ["kitchen"]))
ANSWER = '{"verbal_ack": "OK", "user_intent": {"type": "__intent_grab_object__", "object": "cup_1"}}'


def request() -> ChatRequest:
    context = TurnContext("grab the cup", "person_a", Snapshot(revision=0, entities={}))
    messages = (ChatMessage("system", "be nice"), ChatMessage("user", "grab the cup"))
    return ChatRequest(messages, SCHEMA, context)
