"""Who is speaking, from the name they give when the robot asks: a chat started without a speaker id.

`situated chat` without `--user` greets and asks the person's name (`opening`, the language's
template). The answer names the speaker (`speaker_named`): a person of the KB called so ("Alice":
person_alice), else a new person's id made from the name ("I'm Bob": person_bob, or person_bob_2
when that id is someone else's or no person's). The answer is then that speaker's first turn, after
the robot's question in the dialogue's history, so the rules learn the name from the same words
("Nice to meet you, Bob.") and the engine makes the new id a person of the KB, as for any speaker.

>>> from kb import KB
>>> from dialogue.understanding.language import Language
>>> english = Language.load("en")
>>> told_name(english, "hi, my name is mary jane"), told_name(english, "what do you see?")
('Mary Jane', '')
>>> with KB() as kb:
...     kb += ["person_1 rdf:type Human", 'person_1 rdfs:label "Alice"', "person_bob rdf:type dbr:Cup"]
...     speaker_named(kb, "alice"), speaker_named(kb, "Bob"), speaker_named(kb, "Zoë")
('person_1', 'person_bob_2', 'person_zoe')
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Sequence
from typing import Any, Protocol

from dialogue.reference.english import tokens
from dialogue.understanding.language import Language
from dialogue.understanding.replies import say
from dialogue.understanding.said import Said
from dialogue.understanding.statements.names import clean_name, given_name, name_like

#: The class of the people a name is looked up among, and the prefix of a new person's id.
_PERSON, _ID_PREFIX = "Human", "person_"
#: How many ids a name may try before giving up (person_bob, person_bob_2...).
_MAX_TRIES = 100


class People(Protocol):
    """What finding a speaker reads of the KB: the in-process KB and the service's client both do."""

    def find(self, patterns: list[str], vars: list[str] | None = None,
             models: Sequence[str] | None = None) -> list[dict[str, Any]]: ...


def opening(lang: Language) -> str:
    """The robot's first words to someone it cannot tell who they are: a greeting, asking the name
    (in words the rules take an answer to: "your name")."""
    return say(lang, "introduction.ask_name")


def again(lang: Language) -> str:
    """What the robot says when an answer gave no name."""
    return say(lang, "introduction.ask_name_again")


def told_name(lang: Language, answer: str) -> str:
    """The name an answer to "what is your name?" gives ("Bob", "I'm Bob", "hi, my name is Bob"),
    as it is kept ("bob" -> "Bob"), or "" when it gives none ("what do you see?", "I'm tired")."""
    words = tuple(tokens(lang.ask.lead_in_text.sub("", answer.strip())))
    greeting = next((g for g in lang.social.greetings_longest_first if words[: len(g)] == g), ())
    words = tuple(tokens(lang.ask.lead_in_text.sub("", " ".join(words[len(greeting):]))))
    surely = False
    for lead in (*lang.statements.name_leads_surely, *lang.statements.name_leads):
        if words[: len(lead)] == lead:
            surely, words = lead in lang.statements.name_leads_surely, words[len(lead):]
            break
    if not words:
        return ""
    # The name's words as written (their casing tells names apart), the last ones of the answer.
    written = " ".join(re.findall(r"\S+", answer)[-len(words):]).strip(" .,!?;:")
    told = Said(lang, written)
    name = clean_name(told)
    if not name or not (given_name(lang, words) if surely else name_like(lang, words, told)):
        return ""
    return name


def speaker_named(kb: People, name: str) -> str:
    """The id of the person called `name`: one the KB knows by that name (any case), else a new id
    made from it that names nothing else of the KB."""
    wanted = name.casefold()
    for row in kb.find([f"?p rdf:type {_PERSON}", "?p rdfs:label ?l"]):
        if str(row["l"]).casefold() == wanted:
            return str(row["p"])
    plain = unicodedata.normalize("NFKD", name.lower()).encode("ascii", "ignore").decode()  # "Zoë": zoe
    stem = _ID_PREFIX + ("_".join(re.findall(r"[a-z0-9]+", plain)) or "guest")
    for n in range(1, _MAX_TRIES + 1):
        candidate = stem if n == 1 else f"{stem}_{n}"
        # The candidate is letters, digits and underscores: safe in a pattern as it is.
        classes = {str(row["c"]) for row in kb.find([f"{candidate} rdf:type ?c"])}
        named = kb.find([f"{candidate} rdfs:label ?l"])
        if not classes or (_PERSON in classes and not named):  # free, or a person whose name is not known
            return candidate
    raise ValueError(f"no free id for the name {name!r} after {_MAX_TRIES} tries")
