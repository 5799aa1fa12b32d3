"""One request read against the KB, in order: the intent its roles say (a person taken somewhere
is guided, not carried), the roles the conversation implies, each role grounded to one entity (or
asked for), and the acknowledgement with its intent.

Each step is the interpreter's (dialogue.understanding.interpret), given it as a `Context`."""

from __future__ import annotations

from dataclasses import replace

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.reference.antecedent import antecedent
from dialogue.reference.english import Words, tokens
from dialogue.reference.grounding import Entity
from dialogue.reference.resolution import PERSON, PLACE, ROLE_KINDS, content_words, resolve
from dialogue.understanding.context import Context
from dialogue.understanding.outcome import SPELT_CONFIDENCE, Outcome, Ref
from dialogue.understanding.parsed import Parse
from dialogue.understanding.replies import acknowledgement, hello, say, whose_it_is
from dialogue.understanding.requests.carrying import carried_onto
from dialogue.understanding.requests.ground import ground
from dialogue.understanding.requests.owners import none_yours, whose
from dialogue.understanding.requests.referents import relational

#: The question that asks for a role not said (`replies.toml` [request]), by intent and role, and
#: by role alone.
_ASKED = {
    (I.PLACE_OBJECT, "recipient"): "request.where_put", (I.MOVE_TO, "goal"): "request.where_go",
    (I.GUIDE, "goal"): "request.where_take", (I.SAY, "object"): "request.what_say",
    (I.GUIDE, "recipient"): "request.who_take",
    (I.START_ACTIVITY, "object"): "request.which_activity",
}  # fmt: skip
_EXACTLY = {
    "object": "request.what_exactly", "recipient": "request.whom_exactly", "goal": "request.where_exactly",
}  # fmt: skip
#: How sure the rules are of a request they grounded in full.
_SURE = 0.9

#: The roles of a request grounded: each role's entity (or text), the references, and the things
#: said to be the speaker's ("my book").
_Grounded = tuple[dict[str, str], dict[str, Ref], list[Entity]]


def one_command(c: Context, p: Parse, overrides: dict[str, Words]) -> Outcome:
    """The request, its roles' phrases (`overrides` in place of the parse's) grounded, with its
    acknowledgement; or what is asked, or why it is not understood."""
    slots = {**p.slots, **overrides}
    if "object" not in overrides:  # ("the key card for room 309": one name, not a recipient)
        slots, marks = c.refs.named_across(slots, p.marks)
        p = replace(p, marks=marks)
    if p.double_object and "rest" in slots:
        slots = {**c.refs.split_double_object(slots.pop("rest")), **overrides}
    retargeted = _retargeted(c, p.intent or "", slots)
    if isinstance(retargeted, Outcome):
        return retargeted
    intent, slots = retargeted
    _implied(c, p, intent, slots, overrides)
    grounded = _grounded(c, intent, slots)
    if isinstance(grounded, Outcome):
        return grounded
    return _acknowledged(c, p, intent, slots, grounded)


def _retargeted(c: Context, intent: str, slots: dict[str, Words]) -> Outcome | tuple[str, dict[str, Words]]:
    """The intent the roles say, and the roles for it: a person brought somewhere is guided there,
    a thing returned to a person brought to them, a place needed is where to be taken."""
    if intent in {I.BRING_OBJECT, I.PLACE_OBJECT} and "recipient" in slots:
        # "take Maria to the kitchen", "walk Mr Ito back to the car park": guiding, not carrying
        who = tuple(w for w in slots.get("object", ()) if w not in relational(c.lang))
        # (never to a person: "take them to her" carries them to her)
        if c.refs.person_as_object(who) is not None and who:
            to = slots["recipient"]
            if c.refs.a_person(to) or to in c.lang.requests.brought_here:
                # "bring Sam here": a person brought to a person is no intent the rules have
                return Outcome(say(c.lang, "sorry.not_understood"), understood=False)
            intent, slots = I.GUIDE, {"recipient": who, "goal": slots["recipient"]}
        elif intent == I.PLACE_OBJECT and (
            c.refs.named_person(slots["recipient"]) or c.refs.an_owner(slots["recipient"])
        ):
            intent = I.BRING_OBJECT  # "return the stapler to Carol", "... to its owner": to a person
    if intent == I.BRING_OBJECT and c.refs.a_place(slots.get("object", ())):
        # "I need the lifts": a place is where to be taken, not a thing to carry
        intent, slots = I.GUIDE, {"recipient": slots.get("recipient", ("me",)), "goal": slots["object"]}
    if intent == I.GUIDE and c.refs.someone_else(slots.get("goal", ())):
        # "take me to Marcus", "take me to him": to where he is (unknown: no place, said so by the
        # grounding)
        person = c.refs.person_as_object(slots["goal"])
        if person is not None and person.zone and not c.refs.a_place(slots["goal"]):
            slots["goal"] = tuple(tokens(person.zone))
    return intent, slots


def _implied(c: Context, p: Parse, intent: str, slots: dict[str, Words], overrides: dict[str, Words]) -> None:
    """The roles the conversation says where the words do not (`slots` changed in place)."""
    if intent == I.GUIDE and "goal" in p.implicit and "goal" not in overrides:
        there = antecedent(c.lexicon, c.history, PLACE, place=True, speaker=c.speaker)
        if there is None:  # "take me", "escort Carla", with no place spoken of: asked (whom named)
            slots.pop("goal", None)
    if intent == I.GREET and "recipient" in p.implicit and "recipient" not in overrides:
        # "this is Callum, say hello": whom the same utterance introduced, else the speaker
        person = antecedent(c.lexicon, _this_turn(c), PERSON, speaker=c.speaker)
        slots["recipient"] = tuple(tokens(person.id)) if person is not None else ("me",)
    implicit = "recipient" in p.implicit or not content_words(c.lang, slots.get("recipient", ()))
    if intent == I.GUIDE and slots.get("goal") == ("there",) and implicit:
        # "Ellen needs the utility room, lead the way": the person just spoken of, else the speaker.
        person = antecedent(c.lexicon, c.history, PERSON, speaker=c.speaker)
        slots["recipient"] = tuple(tokens(person.id)) if person is not None else ("me",)
    if "object" in slots:  # "I need biscuits, can you get me some": some of those
        slots["object"] = c.refs.some_of(slots["object"])


def _grounded(c: Context, intent: str, slots: dict[str, Words]) -> Outcome | _Grounded:
    """Each role of the intent grounded to one entity, or the question that asks for one."""
    roles: dict[str, str] = {}
    refs: dict[str, Ref] = {}
    mine: list[Entity] = []  # things said to be the speaker's ("my book")
    spec = I.CATALOGUE[intent]
    for role, kinds in ROLE_KINDS.get(intent, {}).items():
        words = slots.get(role, ())
        if not content_words(c.lang, words) and words not in c.lang.requests.said_there:
            if role in spec.required and set(words) & c.lang.words.demonstratives:
                # "bring me that one": what is pointed at, which the words do not say
                return Outcome(say(c.lang, "sorry.not_understood"), understood=False)
            if role in spec.required:
                return _missing(c, intent, role, roles.get("recipient"))
            continue
        if content_words(c.lang, words)[:1] in ([w] for w in c.lang.words.indefinite):
            # "guide somebody there", "put it somewhere safe": who or where is asked
            return _missing(c, intent, role, roles.get("recipient"))
        owned = c.refs.possessive(words, slots) if role == "object" else whose(c, words, kinds)
        words, owner = owned
        others = [w for r, w in slots.items() if r != role]
        ref = ground(c.refs, words, kinds, role, owner, others)
        if ref.problem is not None:
            return none_yours(c, ref.problem, words, kinds) if owner == c.speaker else ref.problem
        refs[role] = ref
        roles[role] = c.speaker if ref.speaker else (ref.entity.id if ref.entity else "")
        # "my stapler" (not "the folder on my desk": whose the desk is)
        said_mine = slots.get(role, ())[:1] == (c.lang.words.owners.get("mine"),)
        if said_mine and owner == c.speaker and ref.entity is not None and ref.entity.kind == "thing":
            mine.append(ref.entity)
    return roles, refs, mine


def _acknowledged(c: Context, p: Parse, intent: str, slots: dict[str, Words], grounded: _Grounded) -> Outcome:
    """The request with its roles, and the reply that says it back."""
    roles, refs, mine = grounded
    if p.text is not None:
        roles["object"] = p.text
    elif intent in {I.SAY, I.START_ACTIVITY, I.PERFORM_MOTION, I.PRESENT_CONTENT}:
        return _missing(c, intent, "object")
    # The place said back with the preposition it was said with, unless a part of it was named
    # ("in the centre of the table" is put on the table).
    place = slots.get("recipient", ())
    mark = p.marks.get("recipient")
    part_named = set(place) & c.lang.words.parts and "of" in place
    said = " ".join(mark) if mark is not None and not part_named else None
    intent = carried_onto(c.lang, c.snapshot, p, intent, roles)  # "take it to the table"
    reply = acknowledgement(c.lang, c.snapshot, c.speaker, intent, roles, refs, said,
                            c.lexicon.shares_name)  # fmt: skip
    if intent == I.GREET and roles.get("recipient") == c.speaker:  # "say hello": to the speaker
        reply = hello(c.lang, c.snapshot, c.speaker)
    notes = [whose_it_is(c.lang, c.snapshot, e, c.speaker)
             for e in mine if e.owner != c.speaker]  # fmt: skip
    reply = " ".join([*notes, reply])  # "my book" that is Marcus's: said before acting
    if any(ref.guessed for ref in refs.values()):  # "go to bay mine": a guess, less sure
        return Outcome(reply, intent, roles, SPELT_CONFIDENCE, guessed=True)
    return Outcome(reply, intent, roles, _SURE, unsure=_unaccounted(c, intent, slots))


def _this_turn(c: Context) -> tuple[Utterance, ...]:
    """What the speaker said since the robot last spoke (the earlier clauses of this turn)."""
    said = [i for i, u in enumerate(c.history) if u.role == "assistant"]
    return c.history[said[-1] + 1 :] if said else c.history


def _missing(c: Context, intent: str, role: str, whom: str | None = None) -> Outcome:
    """The question that asks for a role not said."""
    # ("show Ana in": where to take her, not "you")
    you = whom in {None, c.speaker}
    them = say(c.lang, "naming.you") if you else c.snapshot.name_of(whom or "")
    key = _ASKED.get((intent, role)) or _EXACTLY.get(role, "request.what_exactly")
    return Outcome(say(c.lang, key, whom=them), clarify=True, open_role=role)


def _unaccounted(c: Context, intent: str, slots: dict[str, Words]) -> bool:
    """Whether a phrase the intent grounds no role of names someone ("salute Olu in the meeting
    room", "water jug to Edith"): words the reading cannot account for."""
    grounded = ROLE_KINDS.get(intent, {})
    if intent == I.STOP_ACTIVITY:  # whatever is said to be stopped, the robot stops
        return False
    for role, words in slots.items():
        if role in grounded or role == "rest":
            continue
        words = words[: words.index("for")] if "for" in words else words  # ("the tour for Jonas": his)
        named = (resolve(c.lexicon, (w,), PERSON).one for w in content_words(c.lang, words))
        if any(person is not None for person in named):
            return True
    return False
