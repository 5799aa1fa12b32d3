"""The root of the dialogue package's errors: ``except DialogueError`` catches every one of them.

Each concrete error stays beside the code that raises it (sessions, intents, schema, prompts, the
model backends, the backend spec, the session store, evaluation). The ones about bad input are also
``ValueError``s, so request models may use their checks as validators.
"""

from __future__ import annotations


class DialogueError(Exception):
    """Something the dialogue engine could not do; the message says what and why."""


class SessionError(DialogueError, ValueError):
    """Unknown dialogue id, unsupported role, or a request that cannot be served; message says which."""


class UnknownDialogue(SessionError):
    """No dialogue has this id (never started, ended, or dropped as the least recently used)."""


class DialogueExists(SessionError):
    """A dialogue is to start with an id another dialogue has (chosen by its caller: a goal's UUID)."""
