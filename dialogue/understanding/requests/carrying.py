"""A thing taken or carried to a piece of furniture that holds things ("carry the toolbox over to the
potting bench", "could you take the tray of nachos to the high table") is put there; taken to a
room, an area or a person ("take the parcel to the office", "take it to her"), or to a table known by
its number ("take the risotto to table four": a table served), it is brought. Which
verbs carry a thing this way is the language's (`requests.toml`: `placing_carriers`); which things
hold others is the ontology's."""

from __future__ import annotations

from dialogue import intents as I
from dialogue.reference.snapshot import Snapshot
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse

#: The ontology's class of furniture that holds objects (tables, shelves).
SUPPORT = "cyc:Object-SupportingFurniture"


def carried_onto(lang: Language, snapshot: Snapshot, p: Parse, intent: str, roles: dict[str, str]) -> str:
    """The intent of a bringing whose verb carries (`p.words[0]`) to the recipient grounded in
    `roles`: a placing when that is a piece of furniture that holds things, else as it was."""
    if intent != I.BRING_OBJECT or not p.words or p.words[0] not in lang.requests.placing_carriers:
        return intent
    place = snapshot.get(roles.get("recipient", ""))
    if place is None or SUPPORT not in place.classes or any(c.isdigit() for c in place.name):
        return intent  # (a table known by its number is where people are served)
    return I.PLACE_OBJECT
