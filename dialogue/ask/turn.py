"""One turn of the ask role on the dialogue engine: ground, read the answer (the offline rules first
when the model has them, else or then the model), advance the form, say the next line.

Who reads an answer follows the model, as for the default role: the rules alone read it offline; a
hybrid model's rules read it first and its LLM only when they understood nothing; a model that reads
prompts itself (`ollama:`, `openai:`, a test model) reads every answer. The rules read English only:
another language goes to the model, or — the rules alone — is answered with `__raw_user_input__`
carrying the locale (the form stays where it was).

The form's state travels between turns as a JSON string (the dialogue's `role_state`); a stateless
(chatbot_msgs 4.0) turn has none, and the form is read again from the history it brings: by the
rules, turn by turn, or by the model, which is given the whole conversation.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Sequence
from dataclasses import replace

from pydantic import ValidationError

from dialogue import intents as I
from dialogue.ask.form import AskForm, FormState, parse_configuration
from dialogue.ask.model import AskPrompts, ask_schema, entity_ids, parse_ask_answer, reading_of
from dialogue.ask.progress import advance, opening_state, question_for
from dialogue.engine import NO_ANSWER_IN_TIME, RULES_ENGLISH_ONLY, DialogueEngine, TurnResult
from dialogue.history import Utterance, role_of
from dialogue.llm.base import ChatMessage, ChatModel, ChatRequest, ModelError, TurnContext
from dialogue.locales import is_english, normalise_locale
from dialogue.reference.lexicon import Lexicon
from dialogue.schema import AnswerError
from dialogue.sessions.rolestate import Progress
from dialogue.trace.record import TraceRecorder
from dialogue.understanding.followups.form import Reading, read_answer

log = logging.getLogger(__name__)
OVER = "this ask dialogue is over (its results are final); start a new one to ask again"


def replay(form: AskForm, history: Sequence[Utterance], lexicon: Lexicon) -> FormState:
    """The form as the rules read the person's answers in `history`, in order."""
    state = opening_state(form)
    for utterance in history:
        if utterance.role == "user" and not state.terminal:
            reading = read_answer(form, state, utterance.text, lexicon, utterance.speaker)
            state, _line = advance(form, state, reading, lexicon, reading.clarify_options)
    return state


def _stored(role_state: str, trace: TraceRecorder) -> FormState | None:
    """The form's stored state; None (read again from the history) when there is none or it is unreadable."""
    if not role_state:
        return None
    try:
        return FormState.from_json(role_state)
    except ValidationError as exc:
        log.error("an ask dialogue's stored form cannot be read, it is read from the history: %s", exc)
        trace.note(f"the stored form could not be read ({exc.error_count()} errors): read from the history")
        return None


class AskRole:
    """The `__ask__` role of the dialogues of one engine."""

    def __init__(self, engine: DialogueEngine, prompts: AskPrompts | None = None) -> None:
        self.engine = engine
        self.prompts = prompts or AskPrompts.load()

    def open(self, configuration: str) -> tuple[str, str]:
        """The opening line (the question) and the form's first state; AskError for a bad configuration."""
        form = parse_configuration(configuration)
        return form.question, opening_state(form).to_json()

    def progress(self, role_state: str) -> Progress:
        """The form's status and the fields obtained so far (an unreadable form: open, none)."""
        try:
            state = FormState.from_json(role_state)
        except ValidationError:
            return Progress()
        return Progress(state.status, state.results())

    async def turn(
        self,
        configuration: str,
        role_state: str,
        text: str,
        *,
        speaker: str,
        history: Sequence[Utterance],
        locale: str | None,
        deadline: float,
        trace: TraceRecorder,
    ) -> tuple[TurnResult, str]:
        form = parse_configuration(configuration)
        locale = normalise_locale(locale) if locale else None
        state = _stored(role_state, trace)
        try:
            async with asyncio.timeout_at(deadline):
                result, state = await self._turn(
                    form, state, text, speaker, tuple(history), locale, deadline, trace
                )
        except TimeoutError:
            result = self.engine.fallback(text, speaker, locale, NO_ANSWER_IN_TIME)
            result = self._again(result, form, state)
        kept = state if state is not None else opening_state(form)
        return self.engine.traced(result, trace), kept.to_json()

    def _again(self, result: TurnResult, form: AskForm, state: FormState | None) -> TurnResult:
        """A turn that read nothing: its reply asks the same question again; the form is unchanged."""
        state = state or opening_state(form)
        asked = question_for(form, state.asked) if state.asked else ""
        reply = f"{result.response} {asked}".strip() if result.response else result.response
        return replace(result, response=reply, dialogue_terminal=state.terminal, results=state.results())

    async def _turn(
        self,
        form: AskForm,
        state: FormState | None,
        text: str,
        speaker: str,
        history: tuple[Utterance, ...],
        locale: str | None,
        deadline: float,
        trace: TraceRecorder,
    ) -> tuple[TurnResult, FormState | None]:
        engine, model = self.engine, self.engine.model
        grounded = await engine.grounded_for(text, speaker, locale, trace)
        if isinstance(grounded, TurnResult):
            return self._again(grounded, form, state), state
        turn = engine.prepare(grounded, text, speaker, history, locale, trace)
        lexicon = grounded[1]
        english = is_english(locale)
        rules_first = model.llm is not model  # the rules alone, or a wrapper with the rules in front
        if state is None:  # a stateless turn: the form is what the history says
            with trace.stage("replay"):
                state = replay(form, history, lexicon) if rules_first and english else opening_state(form)
            trace.note(f"form read from the history: {state.values}")
        if state.terminal:
            return TurnResult(
                "", (), OVER, backend="form", dialogue_terminal=True, results=state.results()
            ), state
        if role_of(speaker) != "user":  # a system update, the robot's own words: no answer of the person
            trace.note(f"{speaker}'s input is no answer: the form is unchanged")
            again = question_for(form, state.asked, lexicon) if state.asked else ""
            unchanged = TurnResult(again, (), backend="form", dialogue_terminal=False,
                                   results=state.results())
            return unchanged, state
        reading: Reading | None = None
        intents: tuple[I.Intent, ...] = ()
        backend, ack, understood = model.name, None, True
        if rules_first and english:
            with trace.stage("rules"):
                reading = read_answer(form, state, text, lexicon, speaker)
            backend = "rules"
            if not reading.understood and model.llm is not None:
                reading = None
        if reading is None:
            llm = model.llm
            if llm is None:  # the rules alone, and not English: handed over, the form unchanged
                raw = I.raw_user_input(text, source=speaker, locale=locale)
                handed = TurnResult(
                    "", (raw,), RULES_ENGLISH_ONLY.format(locale), backend=model.name, understood=False
                )
                return replace(handed, dialogue_terminal=False, results=state.results()), state
            asked = await self._ask_model(form, state, turn.context, lexicon, deadline, llm, trace)
            if isinstance(asked, TurnResult):
                return self._again(asked, form, state), state
            reading, ack = asked
            backend = llm.name
        if not reading.understood:
            intents, understood = (I.raw_user_input(text, source=speaker, locale=locale),), False
        for note in reading.notes:
            trace.note(note)
        new, line = advance(form, state, reading, lexicon, reading.clarify_options)
        if ack and ack.strip() and not english and reading.clarify is None:
            line = ack.strip()  # the model speaks the dialogue's language; the form's lines are English
        clarify = new.clarifying is not None and not new.terminal
        result = TurnResult(
            line,
            intents,
            backend=backend,
            clarify=clarify,
            understood=understood,
            dialogue_terminal=new.terminal,
            results=new.results(),
        )
        return result, new

    async def _ask_model(
        self,
        form: AskForm,
        state: FormState,
        context: TurnContext,
        lexicon: Lexicon,
        deadline: float,
        model: ChatModel,
        trace: TraceRecorder,
    ) -> tuple[Reading, str | None] | TurnResult:
        engine, loop = self.engine, asyncio.get_running_loop()
        snapshot, focus = lexicon.snapshot, context.focus or ()
        ids = entity_ids(form, snapshot, focus)
        schema = ask_schema(form, ids)
        messages = self.prompts.messages(
            form,
            state,
            ids,
            robot_name=context.robot_name,
            speaker=context.speaker,
            text=context.text,
            history=context.history,
            locale=context.locale,
            snapshot=snapshot,
            focus=focus,
            language=engine.prompts,
        )
        request = ChatRequest(messages, schema, context)
        errors: list[str] = []
        for attempt in range(2):
            exchange = trace.request(
                model.name, [(m.role, m.content) for m in request.messages], schema, repair=request.repair
            )
            started = time.perf_counter()
            try:
                with trace.stage("model"):
                    result = await model.chat(request, max(0.01, deadline - loop.time()))
            except ModelError as exc:
                trace.answered(exchange, None, None, started, error=str(exc))
                return engine.fallback(context.text, context.speaker, context.locale, f"{model.name}: {exc}")
            trace.answered(exchange, result.content, result.done_reason, started)
            try:
                with trace.stage("validate"):
                    if not result.understood:
                        raise AnswerError("the model did not understand the input")
                    answer = parse_ask_answer(result.content)
                    return reading_of(answer, form, state, lexicon, context.speaker), answer.verbal_ack
            except AnswerError as exc:
                trace.invalid(exchange, str(exc))
                errors.append(str(exc))
                if attempt == 0:
                    repair = (ChatMessage("assistant", result.content), self.prompts.repair_message(str(exc)))
                    request = ChatRequest((*messages, *repair), schema, context, repair=True)
        why = f"{model.name} gave no valid answer twice: " + " | then: ".join(errors)
        return engine.fallback(context.text, context.speaker, context.locale, why, reply=engine.sorry)
