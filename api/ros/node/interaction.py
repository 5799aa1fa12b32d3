"""chatbot_msgs' DialogueInteraction (``/chatbot/dialogue_interaction``): one entry of a dialogue.

The request's UUID names the dialogue (a ``/chatbot/start_dialogue`` goal's; the nil UUID is the
service's ``default`` dialogue). Which entries are answered is the service's rule (dialogue.sessions.entries):
``response_expected`` false only records, ``__system__`` is a system update, ``__assistant__`` the
robot's own words, an empty input is legal. The turn has the node's ``turn_deadline``, below a
dialogue manager's 5 s: past it the reply is the polite fallback (``__raw_user_input__`` and an
``error_msg``), never no answer. A request the service refuses — an unknown dialogue, an input
longer than REST takes (``max_input_chars``), a locale that is no language tag — gets an empty
response and ``error_msg`` saying why; nothing is recorded.

The callback is a coroutine: the ``/chatbot`` executor runs it as a task that awaits the turn on the
app's loop (``Front.awaited``), so a slow turn does not hold up the node's other callbacks, nor the
other turns.
"""

from __future__ import annotations

from concurrent.futures import TimeoutError as FutureTimeout
from typing import Any

from api.errors import ApiError
from api.limits import check_length
from api.ros.node.front import Front
from api.ros.node.goals import DialogueGoals
from api.ros.node.messages import dialogue_id, intent_messages
from dialogue.engine import TurnResult
from dialogue.errors import DialogueError, UnknownDialogue

#: Seconds the callback waits past the turn's deadline for its answer (recording included).
GRACE = 0.5
START_HINT = "a dialogue is started by a /chatbot/start_dialogue goal, whose UUID is its id"


class Interaction:
    def __init__(self, front: Front, goals: DialogueGoals) -> None:
        self.front = front
        self.goals = goals
        self.dialogues = front.services.dialogues
        self.limit = front.services.settings.limits.max_input_chars

    async def __call__(self, request: Any, response: Any) -> Any:
        response.response, response.intents, response.error_msg = "", [], ""
        try:
            check_length(request.input, self.limit, "input")
            result = await self._turn(dialogue_id(request.dialogue_id), request)
        except UnknownDialogue as exc:
            response.error_msg = f"{exc}; {START_HINT}"
            return response
        except ApiError as exc:
            response.error_msg = exc.message
            return response
        except DialogueError as exc:
            response.error_msg = str(exc)
            return response
        response.response = result.response
        response.intents = intent_messages(result.intents)
        response.error_msg = result.error_msg
        return response

    async def _turn(self, dialogue: str, request: Any) -> TurnResult:
        try:
            return await self._run(dialogue, request)
        except UnknownDialogue:
            if not self.goals.settle():  # no goal was being opened: truly unknown
                raise
            return await self._run(dialogue, request)

    async def _run(self, dialogue: str, request: Any) -> TurnResult:
        deadline = self.front.parameters.turn_deadline
        turn = self.dialogues.interact(request.user_id, request.input, dialogue_id=dialogue,
                                       locale=request.locale or None,
                                       response_expected=request.response_expected, timeout=deadline)
        try:
            return await self.front.awaited(turn, deadline + GRACE)
        except FutureTimeout:
            return self.dialogues.engine.fallback(request.input, request.user_id or "__unknown__",
                                                  request.locale or None,
                                                  f"no answer within the turn's deadline ({deadline:g} s)")
