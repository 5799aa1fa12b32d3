"""Dialogues (chatbot_msgs DialogueInteraction semantics): many at once, each with a bounded history.

`default` always exists. `__assistant__` and `__system__` utterances are recorded with the assistant
and system roles (D14); `response_expected=False` only records. A turn on a dialogue sees that
dialogue's history, and the answer (with the user's words) is appended after the turn.

The dialogues live in a `SessionStore` (dialogue.sessions.store): in this process's memory by default,
or in a store several service processes share (dialogue.sessions.sparql), so a dialogue started on
one process continues on another, a clarifying question asked by one included. Each turn loads the
dialogue's state when it starts and saves it when it ends. The turns of one dialogue run one at a
time in arrival order (dialogue.sessions.turnqueue), yet each turn answers by its own deadline counted from
its arrival: a turn whose deadline passes while earlier ones run gets the engine's polite fallback at
once, and is recorded (its words and that reply) when its place in the queue comes. This holds within
one process only: two processes running turns on the same dialogue at once both load the same
state and the last save wins (the other turn's utterances are lost from the history; its reply and
intents were still returned). A dialogue ended while a turn runs stays ended: the turn's save does
not store it again.

What a turn does depends on the dialogue's role (dialogue.roles): `__default__` (the engine's turn)
or `__ask__` (a form; its question is the dialogue's opening line). A turn that brings its role (the
chatbot_msgs 4.0 stateless shape) reads and writes nothing in the store: the request's history is
the whole dialogue. Every turn's trace is kept, bounded, in `traces` (dialogue.trace), and every
answered turn (stateless ones included) is told to the observers (the intent bus...).
"""

from __future__ import annotations

import asyncio
import logging
import time
import uuid
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import replace
from functools import partial
from typing import Literal, ParamSpec, TypeVar

from dialogue.engine import DialogueEngine, TurnResult
from dialogue.errors import DialogueExists, SessionError, UnknownDialogue
from dialogue.history import ASSISTANT_USER_ID, SYSTEM_USER_ID, History, Utterance
from dialogue.roles import Roles
from dialogue.sessions.entries import (
    answers,
    check_id,
    check_texts,
    check_utterance,
    entry_locale,
    said_nothing,
)
from dialogue.sessions.observers import TurnObserver, TurnRecord, notify
from dialogue.sessions.rolestate import Progress
from dialogue.sessions.store import (
    DEFAULT_DIALOGUE,
    DEFAULT_ROLE,
    DialogueState,
    MemorySessions,
    SessionStore,
    StateError,
    check_bound,
)
from dialogue.sessions.turnqueue import TurnQueue
from dialogue.trace.record import TraceRecorder
from dialogue.trace.store import TraceStore
from kb.errors import KbError, StoreUnavailable

__all__ = [
    "DEFAULT_DIALOGUE",
    "DEFAULT_ROLE",
    "DialogueExists",
    "DialogueManager",
    "DialogueState",
    "SessionError",
    "UnknownDialogue",
    "check_utterance",
    "said_nothing",
]

P = ParamSpec("P")
T = TypeVar("T")
log = logging.getLogger(__name__)


class DialogueManager:
    """Keeps dialogues by id in `store` (default: `MemorySessions(max_dialogues)`); the least
    recently used ones beyond the store's bound are dropped, never `default`.

    `start`, `get`, `end` and `ids` may block on the store: async code calls their `*_async` forms.
    States returned are copies: changing one changes nothing stored.
    """

    def __init__(
        self,
        engine: DialogueEngine,
        *,
        max_dialogues: int = 256,
        max_turns: int = 20,
        max_chars: int = 4000,
        store: SessionStore | None = None,
        observers: Sequence[TurnObserver] = (),
        recall: Callable[[str], Awaitable[str | None]] | None = None,
    ) -> None:
        """`observers` are told of every turn once it has its result (dialogue.sessions.observers);
        `await recall(user_id)` gives a note about the speaker's earlier dialogues that a model
        reading prompts gets before the history (dialogue.memory.people), not blocking the loop."""
        check_bound(max_dialogues)
        History(max_turns, max_chars)  # refuses bad limits now, not at the first turn
        self.engine = engine
        self.roles = Roles(engine)
        #: The recent turns' traces of each dialogue (this process's turns).
        self.traces = TraceStore()
        self.store: SessionStore = store if store is not None else MemorySessions(max_dialogues)
        self.max_dialogues = self.store.max_dialogues
        self.max_turns = max_turns
        self.max_chars = max_chars
        self.observers = tuple(observers)
        self._late_observers: set[asyncio.Task[None]] = set()  # still running after their turn's reply
        self.recall = recall
        #: The turns of each dialogue, one at a time in arrival order.
        self.queue = TurnQueue()

    # -- the store, synchronously ------------------------------------------------------------------
    def _find(self, dialogue_id: str) -> DialogueState | None:
        check_id(dialogue_id)
        try:
            state = self.store.load(dialogue_id)
        except StateError as exc:
            raise SessionError(f"dialogue {dialogue_id!r} cannot be read from the store: {exc}") from None
        if state is None and dialogue_id == DEFAULT_DIALOGUE:
            return DialogueState(DEFAULT_DIALOGUE)
        return state

    def start(
        self,
        role: str = DEFAULT_ROLE,
        locale: str | None = None,
        configuration: str = "",
        dialogue_id: str | None = None,
    ) -> DialogueState:
        opening, role_state = self.roles.get(role).open(configuration)  # a bad configuration is refused
        locale = entry_locale(locale)
        if dialogue_id and self._find(dialogue_id) is not None:
            raise DialogueExists(f"dialogue {dialogue_id!r} already exists: end it first, or choose "
                                 "another id")
        history = (Utterance(ASSISTANT_USER_ID, opening),) if opening else ()
        new_id = dialogue_id or str(uuid.uuid4())
        state = DialogueState(new_id, role, locale, configuration, history, time.time(), role_state)
        self.store.save(state, create=True)
        return state

    @staticmethod
    def opening_line(state: DialogueState) -> str:
        """What the robot says first in a dialogue just started (the ask role's question), or ""."""
        last = state.history[-1] if state.history else None
        return last.text if last is not None and last.speaker == ASSISTANT_USER_ID else ""

    def add_observer(self, observer: TurnObserver) -> None:
        """Tell `observer` of every turn from now on, after the observers given at construction."""
        self.observers = (*self.observers, observer)

    def progress(self, state: DialogueState) -> Progress:
        """Where the dialogue is by its role: open, or over with the role's results."""
        return self.roles.get(state.role).progress(state.role_state)

    def get(self, dialogue_id: str) -> DialogueState:
        state = self._find(dialogue_id)
        if state is None:
            raise UnknownDialogue(f"unknown dialogue {dialogue_id!r}; start it first")
        return state

    def end(self, dialogue_id: str) -> Progress:
        """Forget a dialogue; ending `default` only clears its history (it always exists). Where its
        role was when it ended: still open (ended before the role was done), or over with the results."""
        state = self.get(dialogue_id)
        progress = self.progress(state)
        self.traces.forget(dialogue_id)
        if dialogue_id == DEFAULT_DIALOGUE:
            self.store.save(replace(state, history=(), last_used=time.time()), create=True)
        else:
            self.store.delete(dialogue_id)
        return progress

    def ids(self) -> list[str]:
        """The dialogues, least recently used first (`default` first when it was never used)."""
        stored = self.store.ids()
        return stored if DEFAULT_DIALOGUE in stored else [DEFAULT_DIALOGUE, *stored]

    # -- the same from async code -------------------------------------------------------------------
    async def _off_loop(self, call: Callable[P, T], *args: P.args, **kwargs: P.kwargs) -> T:
        if self.store.blocking:
            return await asyncio.to_thread(call, *args, **kwargs)
        return call(*args, **kwargs)

    async def start_async(
        self,
        role: str = DEFAULT_ROLE,
        locale: str | None = None,
        configuration: str = "",
        dialogue_id: str | None = None,
    ) -> DialogueState:
        return await self._off_loop(self.start, role, locale, configuration, dialogue_id)

    async def get_async(self, dialogue_id: str) -> DialogueState:
        return await self._off_loop(self.get, dialogue_id)

    async def end_async(self, dialogue_id: str) -> Progress:
        return await self._off_loop(self.end, dialogue_id)

    async def ids_async(self) -> list[str]:
        return await self._off_loop(self.ids)

    # -- turns ------------------------------------------------------------------------------------
    def _save(self, state: DialogueState, history: History) -> None:
        # Only `default` is stored anew: any other dialogue ended during the turn stays ended.
        saved = replace(state, history=history.snapshot(), last_used=time.time())
        self.store.save(saved, create=state.id == DEFAULT_DIALOGUE)

    async def interact(
        self,
        user_id: str,
        text: str,
        *,
        dialogue_id: str = DEFAULT_DIALOGUE,
        locale: str | None = None,
        response_expected: bool = True,
        history: Sequence[Utterance] | None = None,
        role: str | None = None,
        configuration: str = "{}",
        summary: str | None = None,
        timeout: float | None = None,
    ) -> TurnResult:
        """One DialogueInteraction (dialogue.sessions.entries: which entries are answered; an empty or
        blank entry is legal). `history` replaces the stored one. With `role` (and its
        `configuration`) the turn is stateless (chatbot_msgs 4.0): nothing is read from or written to
        the store, `dialogue_id` only names the turn (its trace), `history` is the whole dialogue.
        `summary` (of earlier sessions) is given to the turn as a system utterance before the history
        (stored or given); it is not stored.

        Answered within `timeout` seconds (default: the engine's deadline) from now, however many
        turns of the dialogue are queued before this one."""
        if not user_id:
            raise SessionError("user_id is required")
        check_texts(user_id, text, locale, history, [("summary", summary or ""), ("role", role or ""),
                                                      ("configuration", configuration)])
        locale = entry_locale(locale)
        await self.engine.check_speaker(user_id)  # before anything is recorded or learnt
        response_expected = answers(user_id, text, response_expected)
        # Context for this turn only, before its history: never stored, never trimmed away.
        earlier = f"Summary of earlier conversations: {summary}"
        before = (Utterance(SYSTEM_USER_ID, earlier),) if summary else ()
        loop = asyncio.get_running_loop()
        seconds = self.engine.config.deadline if timeout is None else timeout
        deadline = loop.time() + seconds
        if role is not None:
            state = DialogueState(dialogue_id, role, locale, configuration, tuple(history or ()))
            result = await self._stateless(state, user_id, text, response_expected, deadline, before)
            await self._observed(dialogue_id, user_id, text, result, response_expected, deadline)
            return result
        place = await self.queue.take(dialogue_id, deadline - loop.time())
        if not place.reached:
            if response_expected:
                late = self.engine.fallback(
                    text, user_id, locale,
                    f"no answer within the {seconds:g} s deadline: "
                    "earlier turns of this dialogue were still running",
                )
                trace = TraceRecorder(dialogue_id=dialogue_id, speaker=user_id, input=text, locale=locale)
                late = self._traced(dialogue_id, self.engine.traced(late, trace))
            else:
                late = TurnResult("", (), backend="recorded")
            record = partial(self._record_late, dialogue_id, user_id, text, late.response, history)
            self.queue.later(place, record)
            await self._observed(dialogue_id, user_id, text, late, response_expected, deadline)
            return late
        try:
            result = await self._run(dialogue_id, user_id, text, locale, response_expected, history, deadline,
                                     before)
        finally:
            place.release()
        await self._observed(dialogue_id, user_id, text, result, response_expected, deadline)
        return result

    async def _observed(self, dialogue_id: str, user_id: str, text: str, result: TurnResult,
                        response_expected: bool, deadline: float) -> None:
        """Tell the observers, returning by the turn's deadline (what they have not done by then
        goes on after the reply)."""
        if response_expected and self.observers:
            await notify(self.observers, TurnRecord(dialogue_id, user_id, text, result, time.time()),
                         deadline, self._late_observers)

    def _kept(self, state: DialogueState, history: Sequence[Utterance] | None) -> History:
        return History.of(state.history if history is None else history, self.max_turns, self.max_chars)

    async def _run(
        self,
        dialogue_id: str,
        user_id: str,
        text: str,
        locale: str | None,
        response_expected: bool,
        history: Sequence[Utterance] | None,
        deadline: float,
        before: Sequence[Utterance] = (),
    ) -> TurnResult:
        """The turn, holding its dialogue's lock."""
        try:
            state = await self._off_loop(self.get, dialogue_id)
        except StoreUnavailable as exc:  # the turn still answers, politely, in its time
            return self.engine.fallback(text, user_id, locale, f"the dialogue cannot be read: {exc}",
                                        reply=None if response_expected else "")
        kept = self._kept(state, history)
        if not response_expected:
            if not text.strip():  # nothing said: nothing to record
                return TurnResult("", (), backend="recorded")
            kept.add(user_id, text)
            return await self._saved(state, kept, TurnResult("", (), backend="recorded"))
        earlier = await self._recalled(user_id)
        turn_history = (*earlier, *before, *kept.snapshot())
        result, role_state = await self._role_turn(state, user_id, text, turn_history, locale, deadline)
        kept.add(user_id, text)
        if result.response:
            kept.add(ASSISTANT_USER_ID, result.response)
        return await self._saved(replace(state, role_state=role_state), kept, result)

    async def _role_turn(self, state: DialogueState, user_id: str, text: str, history: Sequence[Utterance],
                         locale: str | None, deadline: float,
                         shape: Literal["3.0", "4.0"] = "3.0") -> tuple[TurnResult, str]:
        """The turn as the dialogue's role runs it, its trace kept."""
        locale = locale or state.locale
        trace = TraceRecorder(dialogue_id=state.id, role=state.role, shape=shape, speaker=user_id, input=text,
                              locale=locale)
        result, role_state = await self.roles.get(state.role).turn(
            state.configuration, state.role_state, text, speaker=user_id, history=history, locale=locale,
            deadline=deadline, trace=trace,
        )
        if shape == "4.0":  # the 4.0 response always says whether the dialogue is over, and with what
            terminal, results = bool(result.dialogue_terminal), result.results or "{}"
            told = result.trace and result.trace.model_copy(
                update={"dialogue_terminal": terminal, "results": results})
            result = replace(result, dialogue_terminal=terminal, results=results, trace=told)
        return self._traced(state.id, result), role_state

    def _traced(self, dialogue_id: str, result: TurnResult) -> TurnResult:
        if result.trace is not None:
            self.traces.add(dialogue_id, result.trace)
        return result

    async def _stateless(self, state: DialogueState, user_id: str, text: str, response_expected: bool,
                         deadline: float, before: Sequence[Utterance] = ()) -> TurnResult:
        """A 4.0 turn: its request holds the whole dialogue; the store is not used."""
        role = self.roles.get(state.role)
        if not state.role_state:  # a bad configuration is refused before the turn
            role.open(state.configuration)
        if not response_expected:
            return TurnResult("", (), backend="recorded")
        history = (*before, *self._kept(state, None).snapshot())
        result, _state = await self._role_turn(state, user_id, text, history, state.locale, deadline, "4.0")
        return result

    async def _recalled(self, user_id: str) -> tuple[Utterance, ...]:
        """The note on the speaker's earlier dialogues, for a model that reads prompts only (the
        rules read no notes)."""
        if self.recall is None or self.engine.model.llm is None:
            return ()
        try:
            said = await self.recall(user_id)
        except (KbError, StoreUnavailable) as exc:
            log.warning("no memory of %s for this turn: %s", user_id, exc)
            return ()
        return (Utterance(SYSTEM_USER_ID, said),) if said else ()

    async def _saved(self, state: DialogueState, kept: History, result: TurnResult) -> TurnResult:
        """The turn's result once its history is saved; when the store cannot take it, the result
        still, with an error saying the turn is not in the history."""
        try:
            await self._off_loop(self._save, state, kept)
        except StoreUnavailable as exc:
            log.warning("dialogue %s: the turn is not saved: %s", state.id, exc)
            error = f"the turn is not in the dialogue's history: {exc}"
            return replace(result, error_msg=f"{result.error_msg}; {error}" if result.error_msg else error)
        return result

    async def _record_late(self, dialogue_id: str, user_id: str, text: str, reply: str,
                           history: Sequence[Utterance] | None) -> None:
        """Record a turn answered late, when its place in the queue comes (the order is kept)."""
        try:
            state = await self._off_loop(self.get, dialogue_id)
            kept = self._kept(state, history)
            kept.add(user_id, text)
            if reply:
                kept.add(ASSISTANT_USER_ID, reply)
            await self._off_loop(self._save, state, kept)
        except (SessionError, StoreUnavailable) as exc:  # ended meanwhile, or unreadable
            log.warning("late turn of dialogue %r not recorded: %s", dialogue_id, exc)
