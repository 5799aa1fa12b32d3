"""One dialogue turn: ground -> (prescreen) -> model -> validate -> resolve -> repair once -> reply.

The model is asked, never inspected: `prescreen` may answer from the structured context before any
prompt is built (the rules' fast path, alone or in front of an LLM in a hybrid model), and `llm` is
the model that reads the prompt of the turns it did not answer (None: they are not understood).

The whole turn runs under a deadline. When the model is down, slow or twice invalid, the turn still
answers in time: a polite reply, a `__raw_user_input__` intent and a non-empty `error_msg` (D5).
Referents in emitted intents are always entities of the KB snapshot (or the speaker).
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Sequence
from dataclasses import dataclass, replace

from dialogue import intents as I
from dialogue.earlyack import ask
from dialogue.history import Utterance
from dialogue.llm.base import ChatMessage, ChatModel, ChatRequest, ChatResult, ModelError, TurnContext
from dialogue.llm.rules import RulesModel
from dialogue.prompts import PromptSet
from dialogue.reference.grounding import Entity, Grounder, Snapshot
from dialogue.reference.lexicon import Lexicon, LexiconCache
from dialogue.reference.relevance import mentioned, ranked
from dialogue.schema import AnswerError, SchemaCandidates, parse_answer, turn_schema
from dialogue.speakers import admit
from dialogue.validate import Grounded, ground_answer
from kb import KbError
from kb.protocol import KnowledgeBase
from kb.unicode import check_text

log = logging.getLogger(__name__)

MAX_SCHEMA_IDS = 60
SORRY = "Sorry, I can't answer right now."
NOT_UNDERSTOOD = "Sorry, I did not understand that."


_SUPPORT_CLASSES = frozenset({"PhysicalSupport", "cyc:FurniturePiece", "cyc:Object-SupportingFurniture"})


def _is_support(entity: Entity, held: set[str]) -> bool:
    """Furniture, or anything something else stands on."""
    return entity.id in held or bool(_SUPPORT_CLASSES.intersection(entity.classes))


@dataclass(frozen=True)
class EngineConfig:
    robot_name: str = "robot"
    #: Seconds for the whole turn (dialogue_manager waits 5 s).
    deadline: float = 5.0
    #: Confidence of intents from a model that gives none.
    model_confidence: float = 0.7
    max_snapshot_entities: int = 300
    lang: str = "en"


@dataclass(frozen=True)
class TurnResult:
    response: str
    intents: tuple[I.Intent, ...] = ()
    error_msg: str = ""
    #: Which backend produced the answer ("rules", the model's name, or "fallback").
    backend: str = ""
    clarify: bool = False
    #: False when no backend understood the input (the reply says so).
    understood: bool = True


@dataclass
class _Turn:
    text: str
    speaker: str
    locale: str | None
    context: TurnContext
    lexicon: Lexicon


class DialogueEngine:
    """Stateless per turn; holds the KB, the model and per-revision caches. Safe for many dialogues."""

    def __init__(
        self,
        kb: KnowledgeBase,
        model: ChatModel | None = None,
        config: EngineConfig | None = None,
        prompts: PromptSet | None = None,
    ) -> None:
        self.kb = kb
        self.config = config or EngineConfig()
        self.model: ChatModel = model or RulesModel()
        self.prompts = prompts or PromptSet.load()
        self.grounder = Grounder(self.config.max_snapshot_entities, self.config.lang)
        self._lexicons = LexiconCache()
        self._rebuilds: dict[int, asyncio.Task[tuple[Snapshot, Lexicon]]] = {}

    def ground(self) -> tuple[Snapshot, Lexicon]:
        """The current snapshot and its lexicon (blocking: KB queries on a revision change)."""
        snapshot = self.grounder.snapshot(self.kb)
        return snapshot, self._lexicons.get(snapshot)

    async def ground_async(self) -> tuple[Snapshot, Lexicon]:
        revision = self.kb.revision
        cached = self.grounder.cached(revision)
        if cached is not None:
            return cached, self._lexicons.get(cached)
        # rdflib work (and the lexicon rebuild) never runs on the event loop. One rebuild per
        # revision, shared by every turn that waits for it: with many dialogues, each KB change
        # would otherwise start as many identical rebuilds, all contending for the KB and the GIL.
        loop = asyncio.get_running_loop()
        pending = self._rebuilds.get(revision)
        if pending is None or pending.get_loop() is not loop:
            pending = loop.create_task(asyncio.to_thread(self.ground))
            self._rebuilds = {revision: pending}  # older revisions' rebuilds are of no more use
        # Shielded: a turn that hits its deadline must not cancel the rebuild the others await.
        return await asyncio.shield(pending)

    async def turn(
        self,
        text: str,
        *,
        speaker: str,
        history: Sequence[Utterance] = (),
        locale: str | None = None,
        deadline: float | None = None,
    ) -> TurnResult:
        """One turn, answered by `deadline` (the event loop's clock; default: `config.deadline` s from
        now). A caller that queued the turn passes the deadline counted from its arrival. Text that is
        not valid Unicode (a lone surrogate) is refused with ``kb.unicode.InvalidUnicode`` before
        anything is asked or recorded."""
        check_text(text, "the utterance")
        check_text(speaker, "the speaker")
        loop = asyncio.get_running_loop()
        if deadline is None:
            deadline = loop.time() + self.config.deadline
        try:
            async with asyncio.timeout_at(deadline):
                return await self._turn(text, speaker, tuple(history), locale, deadline)
        except TimeoutError:
            return self.fallback(
                text, speaker, locale, f"no answer within the {self.config.deadline:g} s deadline"
            )

    def fallback(
        self, text: str, speaker: str, locale: str | None, error: str, reply: str = SORRY
    ) -> TurnResult:
        log.warning("dialogue turn fell back to raw user input: %s", error)
        raw = I.raw_user_input(text, source=speaker, locale=locale)
        return TurnResult(reply, (raw,), error or "unknown error", backend="fallback")

    def prepare(
        self,
        grounded: tuple[Snapshot, Lexicon],
        text: str,
        speaker: str,
        history: tuple[Utterance, ...],
        locale: str | None,
    ) -> _Turn:
        snapshot, lexicon = grounded
        focus = ranked(snapshot, speaker, self.config.max_snapshot_entities, mentioned(lexicon, text))
        context = TurnContext(text, speaker, snapshot, history, locale, self.config.robot_name, tuple(focus),
                              lexicon)
        return _Turn(text, speaker, locale, context, lexicon)

    async def _turn(
        self, text: str, speaker: str, history: tuple[Utterance, ...], locale: str | None, deadline: float
    ) -> TurnResult:
        grounded = await self.ground_async()
        if grounded[0].get(speaker) is None:
            try:
                added = await asyncio.to_thread(admit, self.kb, speaker)
            except KbError as exc:
                return self.fallback(text, speaker, locale, f"speaker {speaker!r} cannot join the KB: {exc}")
            if added:  # the speaker is a person of the KB from now on
                grounded = await self.ground_async()
        turn = self.prepare(grounded, text, speaker, history, locale)
        fast = self.fast_path(turn)
        if fast is not None:
            return fast
        llm = self.model.llm
        if llm is None:
            raw = I.raw_user_input(text, source=speaker, locale=locale)
            return TurnResult(NOT_UNDERSTOOD, (raw,), backend=self.model.name, understood=False)
        return await self._ask_model(turn, deadline, llm)

    def fast_path(self, turn: _Turn) -> TurnResult | None:
        """The model's answer without a prompt, grounded (synchronous: pure Python, no KB access)."""
        early = self.model.prescreen(turn.context)
        if early is None:
            return None
        try:
            grounded = ground_answer(early.answer, turn.lexicon, turn.speaker)
        except AnswerError as exc:  # the answer and the contract disagree: let the model (or fallback) answer
            log.error("%s answer for %r failed validation: %s", early.backend, turn.text, exc)
            return None
        clarify = grounded.clarify or early.clarify
        return TurnResult(grounded.reply, grounded.intents, backend=early.backend, clarify=clarify)

    def schema_for(
        self, snapshot: Snapshot, speaker: str, focus: Sequence[Entity] | None = None
    ) -> dict[str, object]:
        """Enums of the `focus` entities (the turn's most relevant first), each capped."""
        pool = ranked(snapshot, speaker, self.config.max_snapshot_entities) if focus is None else focus
        things = [e.id for e in pool if e.kind == "thing"][:MAX_SCHEMA_IDS]
        people = [e.id for e in pool if e.kind == "person"][:MAX_SCHEMA_IDS]
        zones = [e.id for e in pool if e.kind == "zone"][:MAX_SCHEMA_IDS]
        if speaker not in people:
            people.insert(0, speaker)
        # A recipient is a person (bring, greet, guide, say) or a support to put a thing on
        # (place): offering every thing lets small models name an apple as the recipient.
        held = {e.support for e in pool if e.support}
        supports = [e.id for e in pool if e.kind == "thing" and _is_support(e, held)]
        return turn_schema(SchemaCandidates(things, [*people, *supports], [*zones, *things, *people]))

    async def _ask_model(self, turn: _Turn, deadline: float, model: ChatModel) -> TurnResult:
        loop = asyncio.get_running_loop()
        schema = self.schema_for(turn.context.snapshot, turn.speaker, turn.context.focus)
        messages = self.prompts.messages(turn.context)
        request = ChatRequest(messages, schema, turn.context)
        errors: list[str] = []
        for attempt in range(2):
            try:
                result = await ask(model, request, max(0.01, deadline - loop.time()))
            except ModelError as exc:
                return self.fallback(turn.text, turn.speaker, turn.locale, f"{model.name}: {exc}")
            try:
                grounded = self._validate(result, turn)
            except AnswerError as exc:
                errors.append(str(exc))
                if attempt == 0:
                    repair = (ChatMessage("assistant", result.content), self.prompts.repair_message(str(exc)))
                    request = ChatRequest((*messages, *repair), schema, turn.context, repair=True)
                continue
            return TurnResult(grounded.reply, grounded.intents, backend=model.name, clarify=grounded.clarify)
        failed = self.fallback(
            turn.text,
            turn.speaker,
            turn.locale,
            f"{model.name} gave no valid answer twice: " + " | then: ".join(errors),
            reply=NOT_UNDERSTOOD,
        )
        return replace(failed, understood=False)

    def _validate(self, result: ChatResult, turn: _Turn) -> Grounded:
        if not result.understood:
            raise AnswerError("the model did not understand the input")
        answer = parse_answer(result.content)
        return ground_answer(
            answer, turn.lexicon, turn.speaker, default_confidence=self.config.model_confidence
        )
