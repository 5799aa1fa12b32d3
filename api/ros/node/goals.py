"""chatbot_msgs' Dialogue action (``/chatbot/start_dialogue``): each goal is a dialogue of the service.

A goal is checked first: the role is one the service plays, its configuration fits it (the ask
role's form; a JSON object for the default role), the locale is a language tag. A goal that fails
is rejected and the reason logged on the node (``/rosout``): an action's goal response says only
accepted or not. An accepted goal starts a dialogue of the service whose id is the goal's UUID in
its canonical text form, so REST sees the same dialogue (``/dialogues/<uuid>/...``); a goal with
no locale gets the node's ``default_locale``. A dialogue that cannot start (that id exists, the
store is down) aborts the goal with ``error_msg``.

The goal is active while its dialogue is open — its turns come over ``/chatbot/dialogue_interaction``
or REST — and ends:

- SUCCEEDED, with ``results``, when the role says the dialogue is done (the ask role: its form filled);
- ABORTED, with the results so far and ``error_msg``, when the person calls it off, when the
  dialogue is ended elsewhere (``DELETE /dialogues/<id>``) or dropped (more than ``max_dialogues``
  open), or when the service stops;
- CANCELED, with the results so far, when the caller cancels it; the dialogue is ended then.

While open, the goal is ACCEPTED, not EXECUTING: rclpy runs an execute callback as a task that,
while it waits, the executor polls without pause (a core busy per open dialogue). Each goal is
executed once its outcome is known, which ends it at once. A turn tells the goals when its dialogue
ends (a turn observer); a timer on the executor finishes them, sees cancellations, and, each
second, looks for dialogues ended elsewhere.
"""

from __future__ import annotations

import logging
import threading
import time
import uuid
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

from chatbot_msgs.action import Dialogue
from rclpy.action import ActionServer, CancelResponse, GoalResponse

from api.ros.node.front import Front
from dialogue.errors import DialogueError, UnknownDialogue
from dialogue.sessions.entries import entry_locale
from dialogue.sessions.observers import TurnRecord
from dialogue.sessions.rolestate import Progress
from kb.errors import StoreUnavailable

log = logging.getLogger("situated.ros")
#: Seconds between two looks at the open goals (cancel requests, outcomes); and between two
#: looks for their dialogues in the store.
TICK = 0.1
CHECK = 1.0
#: Seconds an interaction waits for a goal just accepted to have its dialogue.
SETTLE = 2.0
#: Seconds `close` waits for the goals it aborts to end, and what they are told.
STOPPING = 2.0
STOPPING_MESSAGE = "the service is stopping"
RESULTS_SENT = 0.2


@dataclass(frozen=True)
class Outcome:
    status: Literal["succeeded", "aborted", "canceled"]
    results: str = "{}"
    error_msg: str = ""


def goal_dialogue_id(handle: Any) -> str:
    return str(uuid.UUID(bytes=bytes(handle.goal_id.uuid)))


def _over(progress: Progress) -> Outcome | None:
    if progress.status == "done":
        return Outcome("succeeded", progress.results)
    if progress.status == "cancelled":
        return Outcome("aborted", progress.results, progress.error_msg)
    return None


class DialogueGoals:
    """The action server and the goals whose dialogues are open."""

    def __init__(self, front: Front) -> None:
        self.front = front
        self.dialogues = front.services.dialogues
        self.node = front.chatbot_node
        self._lock = threading.Lock()
        self._changed = threading.Condition(self._lock)
        #: Open goals by dialogue id.
        self._open: dict[str, Any] = {}
        #: Dialogues a turn found over, for the timer to finish.
        self._flagged: set[str] = set()
        #: Outcomes of goals being executed, by dialogue id.
        self._outcomes: dict[str, Outcome] = {}
        #: When each goal accepted but not opened yet was accepted (oldest first).
        self._accepting: deque[float] = deque()
        self._checked = time.monotonic()
        self._closing = False
        self.server = ActionServer(self.node, Dialogue, "~/start_dialogue", execute_callback=self._finish,
                                   goal_callback=self._check, handle_accepted_callback=self._start,
                                   cancel_callback=self._cancel)
        self.timer = self.node.create_timer(TICK, self._tick)
        self.dialogues.add_observer(self._observe)

    # --- a goal comes ---------------------------------------------------------------------------------
    def _check(self, goal: Any) -> GoalResponse:
        try:
            self.dialogues.roles.get(goal.role.name).open(goal.role.configuration)
            entry_locale(goal.locale)
        except DialogueError as exc:
            self.node.get_logger().error(f"start_dialogue goal rejected: {exc}")
            return GoalResponse.REJECT
        with self._lock:
            self._accepting.append(time.monotonic())
        return GoalResponse.ACCEPT

    def _start(self, handle: Any) -> None:
        dialogue_id = goal_dialogue_id(handle)
        goal = handle.request
        failed: Outcome | None = Outcome("aborted", error_msg=STOPPING_MESSAGE) if self._closing else None
        try:
            if failed is None:
                self.dialogues.start(goal.role.name, goal.locale or self.front.default_locale(),
                                     goal.role.configuration, dialogue_id=dialogue_id)
        except (DialogueError, StoreUnavailable) as exc:
            failed = Outcome("aborted", error_msg=f"the dialogue could not start: {exc}")
        with self._changed:
            if self._accepting:
                self._accepting.popleft()
            if failed is None:
                self._open[dialogue_id] = handle
            self._changed.notify_all()
        if failed is not None:
            self.node.get_logger().error(f"start_dialogue goal {dialogue_id} aborted: {failed.error_msg}")
            self._end(dialogue_id, handle, failed)

    def _cancel(self, handle: Any) -> CancelResponse:
        return CancelResponse.ACCEPT  # the timer ends it once rclpy has marked it cancelling

    def settle(self) -> bool:
        """Wait until the goals accepted by now have their dialogues (at most SETTLE s): an
        interaction may come as soon as its caller has its goal accepted. False: none was pending."""
        with self._changed:
            now = time.monotonic()
            while self._accepting and now - self._accepting[0] > SETTLE:  # a goal rclpy never handed over
                self._accepting.popleft()
            if not self._accepting:
                return False
            self._changed.wait_for(lambda: not self._accepting, SETTLE)
            return True

    # --- a goal ends ----------------------------------------------------------------------------------
    async def _observe(self, record: TurnRecord) -> None:
        """A turn (on the event loop): its dialogue over, the timer ends the goal."""
        if record.result.dialogue_terminal:
            with self._lock:
                if record.dialogue_id in self._open:
                    self._flagged.add(record.dialogue_id)

    def _tick(self) -> None:
        now = time.monotonic()
        look = now - self._checked >= CHECK
        if look:
            self._checked = now
        with self._lock:
            goals, flagged = dict(self._open), self._flagged
            self._flagged = set()
        for dialogue_id, handle in goals.items():
            outcome: Outcome | None = None
            if handle.is_cancel_requested:
                outcome = Outcome("canceled", self._forget(dialogue_id))
            elif dialogue_id in flagged or look:
                outcome = self._looked_up(dialogue_id)
            if outcome is not None:
                self._end(dialogue_id, handle, outcome)

    def _looked_up(self, dialogue_id: str) -> Outcome | None:
        try:
            state = self.dialogues.get(dialogue_id)
        except UnknownDialogue:
            return Outcome("aborted", error_msg=f"dialogue {dialogue_id} was ended elsewhere (DELETE "
                           f"/dialogues/{dialogue_id}) or dropped (more than {self.dialogues.max_dialogues} "
                           "dialogues open)")
        except (DialogueError, StoreUnavailable) as exc:
            log.warning("dialogue %s of a start_dialogue goal cannot be read now: %s", dialogue_id, exc)
            return None
        return _over(self.dialogues.progress(state))

    def _results(self, dialogue_id: str) -> str:
        try:
            return self.dialogues.progress(self.dialogues.get(dialogue_id)).results
        except (DialogueError, StoreUnavailable):
            return "{}"

    def _forget(self, dialogue_id: str) -> str:
        """End the dialogue of a cancelled goal; its results as it ended."""
        try:
            return self.dialogues.end(dialogue_id).results
        except (DialogueError, StoreUnavailable) as exc:
            log.warning("dialogue %s of a cancelled goal was not ended: %s", dialogue_id, exc)
            return self._results(dialogue_id)

    def _end(self, dialogue_id: str, handle: Any, outcome: Outcome) -> None:
        """Execute the goal now that its outcome is known (any thread: rclpy schedules the task)."""
        with self._lock:
            self._open.pop(dialogue_id, None)
            self._outcomes[dialogue_id] = outcome
        handle.execute()

    def _finish(self, handle: Any) -> Any:
        """The execute callback: the goal's known outcome, its terminal state set."""
        with self._lock:
            outcome = self._outcomes.pop(goal_dialogue_id(handle), Outcome("aborted", error_msg="no outcome"))
        ends: dict[str, Callable[[], None]] = {"succeeded": handle.succeed, "aborted": handle.abort,
                                               "canceled": handle.canceled}
        ends[outcome.status]()
        return Dialogue.Result(results=outcome.results, error_msg=outcome.error_msg)

    def close(self) -> None:
        """Abort the open goals (the service stops) and wait a moment for them to end."""
        self._closing = True
        self.settle()  # a goal being opened now is open, or aborted, after this
        self.timer.cancel()
        self.node.destroy_timer(self.timer)
        with self._lock:
            goals = dict(self._open)
        for dialogue_id, handle in goals.items():
            self._end(dialogue_id, handle, Outcome("aborted", self._results(dialogue_id), STOPPING_MESSAGE))
        end = time.monotonic() + STOPPING
        while any(handle.is_active for handle in goals.values()) and time.monotonic() < end:
            time.sleep(0.01)
        # rclpy sends a goal's result right after its terminal state is set, in the same task: a
        # moment for the last of them to go before the server does.
        time.sleep(RESULTS_SENT if goals else 0)
        self.server.destroy()
