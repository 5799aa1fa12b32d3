"""What one dialogue entry (chatbot_msgs DialogueInteraction's input) is, and the checks it passes
before anything is recorded.

An entry is a person's words, a system update (`__system__`: nobody uttered it) or the robot's own
words (`__assistant__`, said elsewhere). Only some entries call for an answer: the robot's own words
are recorded, never answered; a person who said nothing (an empty input, which chatbot_msgs allows)
gets no answer and nothing is recorded (`said_nothing`: over ROS, REST's interactions and the Rasa
webhook alike); a system update, even an empty one, may ask the dialogue's role for its line (the
ask role repeats its question). An edge with nothing to do for a blank utterance refuses it with
`check_utterance` (`/model/parse`: there is nothing to parse).

>>> answers("person_alice", "", True), answers("__system__", "", True), answers("__assistant__", "Hi", True)
(False, True, False)
>>> said_nothing("person_alice", " "), said_nothing("__system__", "")
(True, False)
"""

from __future__ import annotations

from collections.abc import Sequence

from dialogue.errors import SessionError
from dialogue.history import Utterance, role_of
from dialogue.locales import LocaleError, normalise_locale
from kb.errors import InvalidUnicode
from kb.unicode import check_text


def check_utterance(text: str) -> str:
    """`text` when it has something to say; an empty or blank utterance is refused (SessionError,
    a ValueError, so request models may use this as a validator)."""
    if not text.strip():
        raise SessionError("the utterance is empty or blank; say something")
    return text


def said_nothing(user_id: str, text: str) -> bool:
    """Whether the entry is nothing said: empty or blank, and no system update."""
    return not text.strip() and role_of(user_id) != "system"


def answers(user_id: str, text: str, response_expected: bool) -> bool:
    """Whether the entry calls for the role's answer (see the module's docstring)."""
    return response_expected and role_of(user_id) != "assistant" and not said_nothing(user_id, text)


def check_id(dialogue_id: str) -> None:
    try:
        dialogue_id.encode("utf-8")
    except UnicodeEncodeError:
        raise SessionError(f"dialogue id {dialogue_id!r} is not valid Unicode text") from None


def entry_locale(locale: str | None) -> str | None:
    """`ll_CC`, or None for none; SessionError for a locale that is no language tag."""
    try:
        return normalise_locale(locale) if locale else None
    except LocaleError as exc:
        raise SessionError(str(exc)) from None


def check_texts(user_id: str, text: str, locale: str | None, history: Sequence[Utterance] | None,
                extra: Sequence[tuple[str, str]] = ()) -> None:
    """Refuse an entry holding text that is not valid Unicode before anything is recorded."""
    fields = [("user_id", user_id), ("input", text), ("locale", locale or ""), *extra]
    fields += [(f"history turn {i}", part) for i, turn in enumerate(history or ())
               for part in (turn.speaker, turn.text)]
    try:
        for name, value in fields:
            check_text(value, f"the {name}")
    except InvalidUnicode as exc:
        raise SessionError(str(exc)) from None
