"""The offline default model: the rules interpreter behind the ChatModel protocol.

It reads the structured turn context (no prompt parsing) and answers in the same JSON as an LLM, so
its output goes through the same validation and grounding as any model's. Nouns come from the KB
lexicon, so it understands objects it was never shown.
"""

from __future__ import annotations

import json

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, EarlyAnswer, TurnContext
from dialogue.prompts import FREE_FORM_OBJECT
from dialogue.reference.lexicon import LexiconCache
from dialogue.rules.interpret import Interpreter
from dialogue.rules.outcome import Outcome
from dialogue.schema import ChatbotResponse, UserIntent


def _wish(outcome: Outcome) -> UserIntent:
    roles = dict(outcome.roles)
    free = roles.pop("object", None) if outcome.intent in FREE_FORM_OBJECT else None
    return UserIntent(type=outcome.intent, input=free, confidence=outcome.confidence, **roles)


def answer_of(outcome: Outcome) -> ChatbotResponse:
    steps = [o for o in outcome.steps() if o.intent is not None]
    if not steps:
        return ChatbotResponse(verbal_ack=outcome.reply, user_intent=None)
    wishes = [_wish(o) for o in steps]
    return ChatbotResponse(
        verbal_ack=outcome.reply, user_intent=wishes[0], user_intents=wishes if len(wishes) > 1 else None
    )


#: The rules' name, the `backend` of the turns they answer.
RULES = "rules"


class RulesModel(ChatModel):
    """Answers every turn it understands in `prescreen`, without a prompt; reads no prompt itself."""

    def __init__(self) -> None:
        self._lexicons: LexiconCache | None = None  # only for contexts that bring no lexicon

    @property
    def name(self) -> str:
        return RULES

    @property
    def llm(self) -> ChatModel | None:
        return None

    def prescreen(self, context: TurnContext) -> EarlyAnswer | None:
        outcome = self.interpret(context)
        if not outcome.understood:
            return None
        return EarlyAnswer(answer_of(outcome), RULES, clarify=outcome.clarify)

    def interpret(self, context: TurnContext) -> Outcome:
        lexicon = context.lexicon
        if lexicon is None or lexicon.snapshot is not context.snapshot:
            if self._lexicons is None:
                self._lexicons = LexiconCache()
            lexicon = self._lexicons.get(context.snapshot)
        interpreter = Interpreter(lexicon, context.speaker, context.history, context.robot_name)
        return interpreter.interpret(context.text)

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        outcome = self.interpret(request.context)
        answer = answer_of(outcome)
        # The tutorial's two keys, and the list only when there is more than one intent.
        single = answer.user_intents is None
        content = json.dumps(answer.model_dump(exclude={"user_intents"} if single else None))
        return ChatResult(content, "stop", understood=outcome.understood)
