"""Whom a request is said to: a person, not the robot, when it starts with their name and speaks of
their things ("lily put your book on the shelf": someone present) or is set apart as said to them
("Zoe, can you pass me the capo?": someone the KB knows, present or called from elsewhere). The
robot then does nothing ("I think that was for Zoe.")."""

from __future__ import annotations

from dialogue.reference.english import Words
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import PERSON, resolve
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.said import Said


def to_someone_else(lexicon: Lexicon, heard: Said, speaker: str, robot_name: str) -> str | None:
    """The name of the person present the request is said to; None when it may be the robot's."""
    words = list(heard.tokens)
    if len(words) >= 3 and "your" in words[1:]:
        return _present(lexicon, tuple(words[:1]), speaker)
    called = heard.of(heard.text.split(",", 1)[0]).tokens if "," in heard.text else ()
    if not 0 < len(called) < len(words):
        return None
    found = lexicon.mentions(called)  # (only a name: "Bea's plasters, ..." addresses no one)
    if len(found) != 1 or (found[0].start, found[0].end) != (0, len(called)):
        return None
    people = [e for e in found[0].entities if lexicon.is_person(e)]
    person = lexicon.snapshot.get(people[0]) if len(people) == 1 else None
    # (set apart, the name is called whether they are in sight or not: "Dimitri, can you grab...")
    if person is None or person.id == speaker:
        return None
    return person.name if parse(lexicon.lang, heard, robot_name).act == "command" else None


def _present(lexicon: Lexicon, named: Words, speaker: str) -> str | None:
    """The name of the one person present, not the speaker, the words name."""
    person = resolve(lexicon, named, PERSON).one
    if person is None or not person.seen or person.id == speaker:
        return None
    return person.name
