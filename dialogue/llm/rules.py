"""The offline default model: the readers of dialogue.understanding behind the ChatModel protocol.

It reads the structured turn context (no prompt parsing) and answers in the same JSON as an LLM, so
its output goes through the same validation and grounding as any model's. Nouns come from the KB
lexicon, so it understands objects it was never shown.
"""

from __future__ import annotations

import json

from dialogue.llm.base import ChatModel, ChatRequest, ChatResult, EarlyAnswer, TurnContext
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.lexicons import LexiconCache
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.readers import Heard, Turn, interpreted, read
from dialogue.understanding.said import Said

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
        heard = read(self._turn(context))
        if not self._claims(heard):
            if heard.answer.verbal_ack and not heard.answer.user_intent and not heard.answer.user_intents:
                return EarlyAnswer(heard.answer, RULES, understood=False)  # why not understood
            return None
        return EarlyAnswer(heard.answer, RULES, clarify=heard.clarify, confirm=heard.proposes,
                           ends=heard.ends)

    def _turn(self, context: TurnContext) -> Turn:
        lexicon = self._lexicon(context)
        said = context.said  # (the engine's reading of the words, when it made one)
        if said is None or said.lang is not lexicon.lang or said.text != context.text:
            said = Said(lexicon.lang, context.text)  # read once, by every reader
        return Turn(said, lexicon, context.speaker, tuple(context.history), context.robot_name)

    def _lexicon(self, context: TurnContext) -> Lexicon:
        lexicon = context.lexicon
        if lexicon is None or lexicon.snapshot is not context.snapshot:
            if self._lexicons is None:
                self.language = self.language or Language.load()
                self._lexicons = LexiconCache(self.language)
            lexicon = self._lexicons.get(context.snapshot)
        return lexicon

    def interpret(self, context: TurnContext) -> Outcome:
        """The interpreter's reading of the turn (its requests' reader alone)."""
        return interpreted(self._turn(context))

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        heard = read(self._turn(request.context))
        if heard.told:
            return ChatResult(heard.answer.model_dump_json(exclude_none=True), "stop")
        # The tutorial's two keys, and the list only when there is more than one intent.
        unused = {"user_intents"} if heard.answer.user_intents is None else set()
        content = json.dumps(heard.answer.model_dump(exclude=unused | {"facts"}))
        return ChatResult(content, "stop", understood=self._claims(heard))

    def _claims(self, heard: Heard) -> bool:
        """What people know is always claimed; a request only when understood, and a guess or a
        reading proposed for want of evidence ("Shall I...?") only when this model takes guesses (a
        model behind it reads those instead)."""
        sure = not heard.guessed and not heard.proposes
        return heard.told or (heard.understood and (self.take_guesses or sure))
