"""From a validated model answer to intents whose referents are KB entities (D3, D7, D8, D9).

Small models ignore schema enums, so every referent is resolved again: an id of the snapshot, or a
name that resolves to exactly one entity of the right kind. Anything else is an AnswerError whose
message tells the model what was wrong (it is sent back once in a repair request).
"""

from __future__ import annotations

from dataclasses import dataclass

from dialogue import intents as I
from dialogue.memory.claims import Claim, ground_facts
from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import ROLE_KINDS, resolve_id
from dialogue.schema import FREE_FORM_OBJECT, REFERENT_FIELDS, AnswerError, ChatbotResponse, UserIntent
from dialogue.understanding.replies import say

MAX_REPLY_CHARS = 600
MAX_FREE_TEXT_CHARS = 500
#: Required person roles that default to the speaker when the model left them empty (D8 repair).
_SPEAKER_DEFAULTS = {(I.GREET, "recipient"), (I.BRING_OBJECT, "recipient"), (I.GUIDE, "recipient")}


@dataclass(frozen=True)
class Grounded:
    reply: str
    intents: tuple[I.Intent, ...]
    clarify: bool = False
    #: What the person told or asked about the world (learnt after the turn: dialogue.memory).
    claims: tuple[Claim, ...] = ()


def ground_answer(
    answer: ChatbotResponse, lexicon: Lexicon, speaker: str, *, default_confidence: float = 0.7
) -> Grounded:
    """Every intent of the answer grounded, in order; a question about any referent replaces them all."""
    reply = (answer.verbal_ack or "").strip()[:MAX_REPLY_CHARS]
    wishes = answer.wishes()
    told = ground_facts(answer.facts or (), lexicon, speaker)
    if told.question is not None:
        return Grounded(told.question, (), clarify=True)
    if told.refusal is not None:
        return Grounded(told.refusal, ())
    if not wishes:
        if not reply and not told.claims:
            raise AnswerError("both verbal_ack and user_intent are null; say something or give an intent")
        return Grounded(reply, (), claims=told.claims)
    intents: list[I.Intent] = []
    for wish in wishes:
        if wish.type not in I.EXTRACTABLE:
            raise AnswerError(f"user_intent.type {wish.type!r} is not one of {list(I.EXTRACTABLE)}")
        data, question = _roles(wish, lexicon, speaker)
        if question is not None:
            return Grounded(question, (), clarify=True)
        if speaker in data.values() and lexicon.snapshot.get(speaker) is None:
            # no intent names what is not a KB entity (see dialogue.speakers)
            return Grounded(say(lexicon.lang, "sorry.unknown_speaker"), ())
        confidence = wish.confidence if wish.confidence is not None else default_confidence
        try:
            intents.append(I.make_intent(wish.type, data, source=speaker, confidence=confidence))
        except I.IntentError as exc:
            raise AnswerError(str(exc)) from None
    return Grounded(reply or "OK.", tuple(intents), claims=told.claims)


def _roles(wish: UserIntent, lexicon: Lexicon, speaker: str) -> tuple[dict[str, str | None], str | None]:
    intent = wish.type or ""
    kinds = ROLE_KINDS.get(intent, {})
    data: dict[str, str | None] = {}
    values = {f: getattr(wish, f) for f in REFERENT_FIELDS}
    if intent in FREE_FORM_OBJECT:
        # Free-form value (SAY text, activity name): `input`, or `object` from a model that mixed them up.
        obj = values.pop("object")
        text = wish.input if wish.input and wish.input.strip() else obj
        data["object"] = text.strip()[:MAX_FREE_TEXT_CHARS] if text else None
    for field in REFERENT_FIELDS:
        value = values.get(field)
        if field not in kinds:
            continue  # a role this intent does not take is dropped, never passed on (D7)
        if value is None or not value.strip():
            if (intent, field) in _SPEAKER_DEFAULTS:
                data[field] = speaker
            continue
        kind = kinds[field]
        said = value.strip().lower()
        if "person" in kind and (value == speaker or said in lexicon.lang.words.speaker_in_answer):
            data[field] = speaker
            continue
        found = resolve_id(lexicon, value.strip(), kind)
        if found.one is not None:
            data[field] = found.one.id
        elif found.ambiguous:
            return data, clarifying_question(lexicon.lang, lexicon.snapshot, found.matches)
        else:
            # The first of the situation's order (what the robot sees, people, places): naming
            # them costs what they are, not the size of the world.
            allowed = sorted(e.id for e in lexicon.snapshot.first_of_kind(kind, 30))
            raise AnswerError(
                f"{field} {value!r} is not the id of a {'/'.join(sorted(kind))} in the situation; "
                f"use one of {allowed} or null"
            )
    return data, None
