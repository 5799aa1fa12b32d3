"""One dialogue turn: ground -> (prescreen) -> model -> validate -> resolve -> repair once -> reply.

The model is asked, never inspected: `prescreen` may answer from the structured context before any
prompt is built (the rules' fast path, alone or in front of an LLM in a hybrid model), and `llm` is
the model that reads the prompt of the turns it did not answer (None: they are not understood).

The whole turn runs under a deadline. When the model is down, slow or twice invalid, the turn still
answers in time: a polite reply, a `__raw_user_input__` intent and a non-empty `error_msg` (D5).
Referents in emitted intents are always entities of the KB snapshot (or the speaker).

Every turn is traced as data (dialogue.trace): each stage timed, each model request with its
messages, schema, raw answer and validation error; the result carries the finished `TurnTrace`.
The offline rules read English only (dialogue.locales): a turn in another language skips them.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

from dialogue import intents as I
from dialogue.earlyack import ask
from dialogue.history import Utterance
from dialogue.llm.base import ChatMessage, ChatModel, ChatRequest, ChatResult, ModelError, TurnContext
from dialogue.llm.rules import RulesModel
from dialogue.locales import is_english, normalise_locale
from dialogue.memory.claims import Claim
from dialogue.memory.learn import Memory
from dialogue.memory.replies import confirmation
from dialogue.prompts import PromptSet
from dialogue.reference.grounding import Entity, Grounder, Snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.lexicons import LexiconCache
from dialogue.reference.relevance import Focus, mentioned, ranked
from dialogue.schema import AnswerError, SchemaCandidates, parse_answer, turn_schema
from dialogue.speakers import NOT_PEOPLE, admit, check_speaker
from dialogue.trace.record import AnsweredBy, TraceRecorder, TurnTrace
from dialogue.understanding.language import Language
from dialogue.understanding.replies import say
from dialogue.understanding.said import Said
from dialogue.validate import Grounded, ground_answer
from kb import KbError
from kb.protocol import KnowledgeBase
from kb.unicode import check_text

log = logging.getLogger(__name__)

MAX_SCHEMA_IDS = 60
NO_ANSWER_IN_TIME = "no answer by the turn's deadline"
RULES_ENGLISH_ONLY = "the offline rules understand English only; a model backend (hybrid:...) reads locale {}"


_SUPPORT_CLASSES = frozenset({"PhysicalSupport", "cyc:FurniturePiece", "cyc:Object-SupportingFurniture"})


def sorry(lang: Language | None = None) -> str:
    """What the engine says when no answer comes in time (the `sorry.cannot_answer_now` template of
    `lang`, by default the packaged English)."""
    return say(lang or Language.load(), "sorry.cannot_answer_now")


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
    #: The reply proposes a reading and asks whether to act on it ("Shall I...?"), acting on none.
    confirm: bool = False
    #: A role's dialogue is over (the ask role: every field obtained, or the person cancelled; the
    #: default role: the person took leave).
    dialogue_terminal: bool | None = None
    #: The role's results, a JSON object string (the ask role: the fields obtained).
    results: str | None = None
    trace: TurnTrace | None = None
    #: What the person told or asked about the world; learnt (dialogue.memory) before the reply.
    claims: tuple[Claim, ...] = ()


@dataclass
class _Turn:
    text: str
    speaker: str
    locale: str | None
    context: TurnContext
    lexicon: Lexicon
    trace: TraceRecorder


class DialogueEngine:
    """Stateless per turn; holds the KB, the model and per-revision caches. Safe for many dialogues."""

    def __init__(
        self,
        kb: KnowledgeBase,
        model: ChatModel | None = None,
        config: EngineConfig | None = None,
        prompts: PromptSet | None = None,
        memory: Memory | None = None,
        language: Language | None = None,
    ) -> None:
        self.kb = kb
        #: Learns what people tell the robot (default: the `people` trust policy).
        self.memory = memory or Memory(kb)
        self.config = config or EngineConfig()
        self.model: ChatModel = model or RulesModel()
        self.prompts = prompts or PromptSet.load()
        #: The language the rules read and the KB's names are said in (English by default), read once.
        self.language = language or Language.load()
        self._lexicons = LexiconCache(self.language)
        # Whoever makes a snapshot makes its lexicon too: a turn that finds a snapshot finds both.
        self.grounder = Grounder(self.config.max_snapshot_entities, self.config.lang, then=self._lexicons.get)
        self._rebuilds: dict[int, asyncio.Task[tuple[Snapshot, Lexicon]]] = {}

    def follow(self, built: Callable[[], object] | None = None) -> None:
        """Keep the grounding current from the KB's commits on a worker thread (the service's
        engine does): the first snapshot is built there, and a turn after any quiet spell finds
        the changes taken up. Without it, each turn takes up the commits made since the last.
        ``built`` is called after each full build of the grounding."""
        self.grounder.follow(self.kb, built)

    def close(self) -> None:
        """Stop following the KB (the worker ends)."""
        self.grounder.close()

    def ground(self) -> tuple[Snapshot, Lexicon]:
        """The current snapshot and its lexicon (blocking: KB queries on a revision change)."""
        snapshot = self.grounder.snapshot(self.kb)
        return snapshot, self._lexicons.get(snapshot)

    async def ground_async(self) -> tuple[Snapshot, Lexicon]:
        revision = self.kb.revision
        cached = self.grounder.cached(revision)
        lexicon = self._lexicons.made(cached) if cached is not None else None
        if cached is not None and lexicon is not None:
            return cached, lexicon
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
        trace: TraceRecorder | None = None,
    ) -> TurnResult:
        """One turn, answered by `deadline` (the event loop's clock; default: `config.deadline` s from
        now). A caller that queued the turn passes the deadline counted from its arrival. Text that is
        not valid Unicode (a lone surrogate) is refused with ``kb.unicode.InvalidUnicode``, a locale that
        is no language tag with ``dialogue.locales.LocaleError``, before anything is asked or recorded."""
        check_text(text, "the utterance")
        check_text(speaker, "the speaker")
        locale = normalise_locale(locale) if locale else None
        loop = asyncio.get_running_loop()
        if deadline is None:
            deadline = loop.time() + self.config.deadline
        recorder = trace or TraceRecorder(speaker=speaker, input=text, locale=locale)
        try:
            async with asyncio.timeout_at(deadline):
                result = await self._turn(text, speaker, tuple(history), locale, deadline, recorder)
                if result.claims:  # learning is part of the turn: within its deadline too
                    result = await self._remember(result, text, speaker)
        except TimeoutError:
            result = self.fallback(text, speaker, locale, NO_ANSWER_IN_TIME)
        return self.traced(result, recorder)

    def traced(self, result: TurnResult, recorder: TraceRecorder) -> TurnResult:
        """`result` carrying its finished trace."""
        trace = recorder.finish(
            response=result.response, backend=result.backend,
            answered_by=_answered_by(result, self.model, recorder.trace.locale),
            intents=result.intents, error_msg=result.error_msg, clarify=result.clarify,
            dialogue_terminal=result.dialogue_terminal, results=result.results,
        )
        return replace(result, trace=trace)

    async def _remember(self, result: TurnResult, text: str, speaker: str) -> TurnResult:
        """Learn what the turn was told (or answer what it was asked about it) and say so: the
        reply to the intents, if any, then one sentence per claim (dialogue.memory)."""
        snapshot, _ = await self.ground_async()
        try:
            settled = await asyncio.to_thread(
                self.memory.settle, result.claims, speaker=speaker, text=text, snapshot=snapshot
            )
        except KbError as exc:
            log.warning("what %r said was not learnt: %s", speaker, exc)
            return replace(result, response=say(self.language, "sorry.not_remembered"),
                           error_msg=f"the KB refused what was learnt: {exc}")
        said = confirmation(self.language, settled, snapshot, speaker)
        kept = result.response if result.intents else ""
        return replace(result, response=" ".join(p for p in (kept, said) if p))

    def fallback(
        self, text: str, speaker: str, locale: str | None, error: str, reply: str | None = None
    ) -> TurnResult:
        """The turn as raw user input, with `reply` (by default `sorry`)."""
        log.warning("dialogue turn fell back to raw user input: %s", error)
        raw = I.raw_user_input(text, source=speaker, locale=locale)
        said = self.sorry if reply is None else reply
        return TurnResult(said, (raw,), error or "unknown error", backend="fallback")

    @property
    def sorry(self) -> str:
        """What the engine says when no answer comes in time."""
        return sorry(self.language)

    def prepare(
        self,
        grounded: tuple[Snapshot, Lexicon],
        text: str,
        speaker: str,
        history: tuple[Utterance, ...],
        locale: str | None,
        trace: TraceRecorder | None = None,
    ) -> _Turn:
        snapshot, lexicon = grounded
        said = Said(lexicon.lang, text)  # the turn's words, read once: what it names, and the rules
        recorder = trace or TraceRecorder(speaker=speaker, input=text, locale=locale)
        recorder.snapshot(snapshot.revision, len(snapshot.entities))
        # Ranked only if a prompt or a schema reads it (never for a turn the rules answer).
        focus = Focus(snapshot, speaker, self.config.max_snapshot_entities,
                      lambda: mentioned(lexicon, said.tokens),
                      then=lambda shown: recorder.shown([e.kind for e in shown], [e.id for e in shown]))
        robot_name = snapshot.robot_name(self.config.robot_name)
        context = TurnContext(text, speaker, snapshot, history, locale, robot_name, focus,
                              lexicon, said)
        return _Turn(text, speaker, locale, context, lexicon, recorder)

    async def check_speaker(self, speaker: str, what: str = "user_id") -> None:
        """Refuse (dialogue.speakers.NotAPerson) a speaker's id that names something of the KB that is
        no person; a person of the current snapshot passes without a KB read. Never waits for the
        grounding: it comes before a turn's deadline is set (a snapshot not made yet, the first one
        at start, takes seconds), and the KB can always say it."""
        if speaker in NOT_PEOPLE:
            return
        snapshot = self.grounder.cached(self.kb.revision)
        entity = snapshot.get(speaker) if snapshot is not None else None
        if entity is None or entity.kind != "person":
            await asyncio.to_thread(check_speaker, self.kb, speaker, what)

    async def grounded_for(
        self, text: str, speaker: str, locale: str | None, trace: TraceRecorder
    ) -> tuple[Snapshot, Lexicon] | TurnResult:
        """The turn's snapshot and lexicon, the speaker a person of the KB; a fallback when they cannot be."""
        with trace.stage("ground"):
            grounded = await self.ground_async()
        if grounded[0].get(speaker) is None:
            with trace.stage("speaker"):
                try:
                    added = await asyncio.to_thread(admit, self.kb, speaker)
                except KbError as exc:
                    why = f"speaker {speaker!r} cannot join the KB: {exc}"
                    return self.fallback(text, speaker, locale, why)
                if added:  # the speaker is a person of the KB from now on
                    grounded = await self.ground_async()
        return grounded

    async def _turn(
        self, text: str, speaker: str, history: tuple[Utterance, ...], locale: str | None, deadline: float,
        trace: TraceRecorder,
    ) -> TurnResult:
        grounded = await self.grounded_for(text, speaker, locale, trace)
        if isinstance(grounded, TurnResult):
            return grounded
        turn = self.prepare(grounded, text, speaker, history, locale, trace)
        english = is_english(locale)
        if english:  # the rules read English only: never an English misparse of another language
            with trace.stage("rules"):
                fast = self.fast_path(turn)
            if fast is not None:
                return fast
        llm = self.model.llm
        if llm is None:
            if not english:
                raw = I.raw_user_input(text, source=speaker, locale=locale)
                return TurnResult("", (raw,), RULES_ENGLISH_ONLY.format(locale), backend=self.model.name,
                                  understood=False)
            return self._declined(turn, None)
        return await self._ask_model(turn, deadline, llm)

    def fast_path(self, turn: _Turn) -> TurnResult | None:
        """The model's answer without a prompt, grounded (synchronous: pure Python, no KB access)."""
        early = self.model.prescreen(turn.context)
        if early is None:
            return None
        if not early.understood:  # only why not: a model behind reads the turn, else the why is said
            return None if self.model.llm is not None else self._declined(turn, early.answer.verbal_ack)
        try:
            grounded = ground_answer(early.answer, turn.lexicon, turn.speaker)
        except AnswerError as exc:  # the answer and the contract disagree: let the model (or fallback) answer
            log.error("%s answer for %r failed validation: %s", early.backend, turn.text, exc)
            return None
        clarify = grounded.clarify or early.clarify
        return TurnResult(grounded.reply, grounded.intents, backend=early.backend, clarify=clarify,
                          claims=grounded.claims, confirm=early.confirm, dialogue_terminal=early.ends or None)

    def _declined(self, turn: _Turn, why: str | None) -> TurnResult:
        """The turn no backend understood: the raw input for the middleware, and why (or that) not."""
        raw = I.raw_user_input(turn.text, source=turn.speaker, locale=turn.locale)
        why = why or say(self.language, "sorry.not_understood")
        return TurnResult(why, (raw,), backend=self.model.name, understood=False)

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
            exchange = turn.trace.request(model.name, [(m.role, m.content) for m in request.messages], schema,
                                          repair=request.repair)
            started = time.perf_counter()
            try:
                with turn.trace.stage("model"):
                    result = await ask(model, request, max(0.01, deadline - loop.time()))
            except ModelError as exc:
                turn.trace.answered(exchange, None, None, started, error=str(exc))
                return self.fallback(turn.text, turn.speaker, turn.locale, f"{model.name}: {exc}")
            turn.trace.answered(exchange, result.content, result.done_reason, started)
            try:
                with turn.trace.stage("validate"):
                    grounded = self._validate(result, turn)
            except AnswerError as exc:
                turn.trace.invalid(exchange, str(exc))
                errors.append(str(exc))
                if attempt == 0:
                    repair = (ChatMessage("assistant", result.content), self.prompts.repair_message(str(exc)))
                    request = ChatRequest((*messages, *repair), schema, turn.context, repair=True)
                continue
            return TurnResult(grounded.reply, grounded.intents, backend=model.name, clarify=grounded.clarify,
                              claims=grounded.claims)
        failed = self.fallback(
            turn.text,
            turn.speaker,
            turn.locale,
            f"{model.name} gave no valid answer twice: " + " | then: ".join(errors),
            reply=say(self.language, "sorry.not_understood"),
        )
        return replace(failed, understood=False)

    def _validate(self, result: ChatResult, turn: _Turn) -> Grounded:
        if not result.understood:
            raise AnswerError("the model did not understand the input")
        answer = parse_answer(result.content)
        return ground_answer(
            answer, turn.lexicon, turn.speaker, default_confidence=self.config.model_confidence
        )


#: Results no backend gave: the fallback, a recorded utterance, a role's own answer ("form").
_NO_BACKEND: dict[str, AnsweredBy] = {"fallback": "fallback", "recorded": "recorded", "form": "form"}


def _answered_by(result: TurnResult, model: ChatModel, locale: str | None) -> AnsweredBy:
    """Which kind of backend answered the turn, for its trace."""
    own = _NO_BACKEND.get(result.backend)
    if own is not None:
        return own
    if not result.understood and model.llm is None and not is_english(locale):
        return "handover"
    return "rules" if result.backend == "rules" else "model"
