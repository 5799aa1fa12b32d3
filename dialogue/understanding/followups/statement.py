"""An answer to the robot's question about a statement: "the mug is mine" -> "Which cup do you mean:
the red one or the blue one?" -> "the red one" learns that the red mug is theirs.

The statement is read again with its ambiguous phrase completed by the answer ("the red one" for
"the mug": "red mug"; "the one on the shelf": "mug on the shelf"), as the command grammar completes
a pending request (dialogue.understanding.interpret).
"""

from __future__ import annotations

from collections.abc import Sequence

from dialogue.history import Utterance
from dialogue.reference.lexicon import Lexicon
from dialogue.understanding.said import Text
from dialogue.understanding.speech.repair import normalise
from dialogue.understanding.statements.grammar import Statements, Told, Words


def follow_up(text: Text, lexicon: Lexicon, speaker: str, history: Sequence[Utterance]) -> Told | None:
    """The statement the robot asked about, completed by `text`; None when `text` answers no
    question of the robot's about a statement (or does not settle it)."""
    spoken = [i for i, u in enumerate(history) if u.role != "system"]
    if len(spoken) < 2:
        return None
    question, request = history[spoken[-1]], history[spoken[-2]]
    if question.role != "assistant" or not question.text.rstrip().endswith("?") or request.role != "user":
        return None
    before = history[: spoken[-2]]
    earlier = Statements(lexicon, speaker, before)
    first = earlier.read(request.text)
    phrase = earlier.open_phrase
    if first is None or not first.clarify or phrase is None:
        return None
    said = lexicon.lang.followups
    fragment: Words = tuple(w for w in normalise(lexicon.lang, text) if w not in said.emphasis)
    if not fragment:
        return None
    head = tuple(w for w in phrase if w not in said.articles)
    if set(fragment) & said.one:  # "the red one": the phrase's words in place of "one"
        merged = tuple(x for w in fragment for x in (head if w in said.one else (w,)))
    else:
        merged = (*fragment, *head)
    told = Statements(lexicon, speaker, before, {phrase: merged}).read(request.text)
    return told if told is not None and (told.facts or told.clarify) else None
