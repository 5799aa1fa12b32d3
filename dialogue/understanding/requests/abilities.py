"""Whether a request may only ask what the robot can do ("can you dance?", "are you able to cook",
"can you do a cartwheel", "Pip, can you cook dinner?"): a question of a verb alone or of a
performance or chore (`requests.toml`: `abilities`, `performances`), which the rules only propose
("Shall I dance?") — unless it is an activity beyond the robot's skills (`requests/skills`: "I can't
cook dinner myself")."""

from __future__ import annotations

from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse
from dialogue.understanding.said import Said
from dialogue.understanding.speech.plain import expanded
from dialogue.understanding.speech.repair import strip_vocative


def asks_ability(lang: Language, heard: Said, p: Parse, robot_name: str = "") -> bool:
    """Whether the words ask what the robot can do, said first or after a name the request is said
    to ("pip can you do my homework"): a question that may ask no more than that."""
    said = tuple(expanded(lang, heard))
    starts = [said]
    if said and strip_vocative(lang, list(said), robot_name) != list(said):
        starts.append(said[1:])
    asked = any(s[: len(a)] == a for s in starts for a in lang.requests.abilities)
    performed = any(p.words[: len(f)] == f for f in lang.requests.performances)
    return asked and p.act == "command" and (len(p.words) == 1 or performed)
