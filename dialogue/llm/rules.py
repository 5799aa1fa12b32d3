"""The offline default model: the rules interpreter behind the ChatModel protocol.

It reads the structured turn context (no prompt parsing) and answers in the same JSON as an LLM, so
its output goes through the same validation and grounding as any model's. Nouns come from the KB
lexicon, so it understands objects it was never shown.
"""

from __future__ import annotations

import json

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, EarlyAnswer, TurnContext
from dialogue.prompts import FREE_FORM_OBJECT
from dialogue.reference.lexicon import Lexicon, LexiconCache
from dialogue.schema import ChatbotResponse, UserIntent
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.statements.reading import Reading, read_turn


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

    def __init__(self, take_guesses: bool = True, language: Language | None = None) -> None:
        #: The language of the lexicons this model makes itself, for contexts that bring none
        #: (English when not given, read then).
        self.language = language
        self._lexicons: LexiconCache | None = None  # only for contexts that bring no lexicon
        #: Whether a turn in which a misspelt word was read as a KB name ("the thremos") is
        #: answered (alone, the rules' best reading), or left to the model behind (hybrid).
        self.take_guesses = take_guesses

    @property
    def name(self) -> str:
        return RULES

    @property
    def llm(self) -> ChatModel | None:
        return None

    def prescreen(self, context: TurnContext) -> EarlyAnswer | None:
        told = self.told(context)
        if told is not None:  # what people tell or ask about what they know (dialogue.memory)
            return EarlyAnswer(told.answer, RULES, clarify=told.clarify)
        outcome = self.interpret(context)
        if not self._claims(outcome):
            return None
        return EarlyAnswer(answer_of(outcome), RULES, clarify=outcome.clarify)

    def told(self, context: TurnContext) -> Reading | None:
        return read_turn(context.text, self._lexicon(context), context.speaker, context.history)

    def _lexicon(self, context: TurnContext) -> Lexicon:
        lexicon = context.lexicon
        if lexicon is None or lexicon.snapshot is not context.snapshot:
            if self._lexicons is None:
                self.language = self.language or Language.load()
                self._lexicons = LexiconCache(self.language)
            lexicon = self._lexicons.get(context.snapshot)
        return lexicon

    def interpret(self, context: TurnContext) -> Outcome:
        lexicon = self._lexicon(context)
        interpreter = Interpreter(lexicon, context.speaker, context.history, context.robot_name)
        return interpreter.interpret(context.text)

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        told = self.told(request.context)
        if told is not None:
            return ChatResult(told.answer.model_dump_json(exclude_none=True), "stop")
        outcome = self.interpret(request.context)
        answer = answer_of(outcome)
        # The tutorial's two keys, and the list only when there is more than one intent.
        unused = {"user_intents"} if answer.user_intents is None else set()
        content = json.dumps(answer.model_dump(exclude=unused | {"facts"}))
        return ChatResult(content, "stop", understood=self._claims(outcome))

    def _claims(self, outcome: Outcome) -> bool:
        return outcome.understood and (self.take_guesses or not outcome.guesses)
