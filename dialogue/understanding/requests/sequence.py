"""A compound request read part by part ("go to the kitchen and take the plate"): what each part
asks for, in order, and what the parts say together.

Each part is read as a request of its own, with the parts before it as context for its pronouns
("take the book and put it in the oven"). A part the robot has no intent for ("... and inspect it",
"... and count the chairs", "... and tell me how many there are") does not sink the others: they are
done and the reply says which part cannot be. Going to someone and then engaging with them ("go over
to Jen and have a chat with her") is the engaging. A thing fetched and then handed on to someone
("fetch the juice from the fridge and give it to Amara") is one bringing; taken and then carried on
("pick up the book and bring it to me", "bring the mug and put it on the tray") it is taken, not
brought to the speaker first.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.reference.antecedent import antecedent
from dialogue.reference.english import tokens
from dialogue.reference.resolution import ROLE_KINDS
from dialogue.understanding.context import Reader
from dialogue.understanding.followups.proposal import proposed
from dialogue.understanding.outcome import Outcome, Ref
from dialogue.understanding.replies import acknowledgement, said_back, say, then
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.requests.compound import Part
from dialogue.understanding.requests.skills import skilled
from dialogue.understanding.requests.staying import left_as_is
from dialogue.understanding.said import Said

#: What a thing carried on to someone or somewhere is, carried first: taken.
_HANDED_ON = frozenset({I.BRING_OBJECT, I.PLACE_OBJECT})


def compound(reader: Reader, heard: Said, parts: Sequence[Part]) -> Outcome | None:
    """Every part read in order: the intents, or the question about a part that must come first, or
    None when a part is not understood (the whole is then read otherwise)."""
    done: list[Outcome] = []
    verbs: list[str | None] = []  # the verb of each part done
    cannot: list[Said] = []
    staying_before: list[str] = []  # the acknowledgements of things left where they are
    staying_after: list[str] = []
    context: list[Utterance] = []
    aside = False
    for n, part in enumerate(parts):
        within = reader.within((*reader.history, *context))
        context.append(Utterance(reader.speaker, part.text))
        if n == 0 and part.verb is None:
            if _asks(reader, heard.of(part.text)):
                return None  # "where have they gone and put my stick": one question, no parts
            continue  # a preamble ("hey there", "thanks", "the denim jacket"): context for the rest
        if part.aside and n < len(parts) - 1:
            aside = True  # "move out of the way and go to the door": the going does it
            continue
        said = heard.of(part.text)
        stays = left_as_is(within, parse(reader.lang, said, reader.robot_name))
        if stays is not None:  # "leave it there and bring me the charger": acknowledged, nothing to do
            (staying_after if done else staying_before).append(stays.reply)
            continue
        outcome = within.part(said)
        if n == 1 and parts[0].verb is None:  # "I want the pear, can you get it": brought to me
            outcome = wished(reader, heard, [parts[0].text], dropped(within, said, [parts[0].text], outcome))
        if outcome.intent is not None and done and (outcome.intent, outcome.roles) == (
            done[-1].intent, done[-1].roles):
            continue  # "go to the shed and wait there": one move
        if _joins(done[-1:], outcome):
            done[-1], verbs[-1] = outcome, part.verb  # "go over to Jen and have a chat with her"
            continue
        if outcome.intent is not None:
            done.append(outcome)
            verbs.append(part.verb)
            if outcome.roles.get("object") in reader.snapshot.entities:
                # "get the teddy off the bench and give it to Zara": "it" is what was taken
                context.append(Utterance(reader.speaker, outcome.roles["object"]))
        elif outcome.clarify:
            return outcome  # ask about this part first: nothing is done until it is clear
        elif part.no_intent or _unskilled(reader, said) or (done and _asks(reader, said)):
            # ("go to the kitchen and tell me what's there": answered now, it would answer wrong)
            cannot.append(heard.of(part.text))
        else:  # a part that fails says why; one not understood makes the whole not understood
            return outcome if outcome.understood else None
    if not done or (aside and not {o.intent for o in done} & {I.MOVE_TO, I.GUIDE}):
        return None  # (out of the way, then no going anywhere: not understood)
    done = _taken_first(reader, _fetched_for(reader, done, verbs))
    lang = reader.lang
    acks = [*staying_before, then(lang, [o.reply for o in done]), *staying_after]
    unable = [say(lang, "request.cannot", action=said_back(lang, c.written)) for c in cannot]
    whole = replace(done[0], reply=" ".join([*acks, *unable]), more=tuple(done[1:]))
    if whole.doubts:  # each part said back in the question
        return proposed(lang, whole, [o.reply for o in done], unable)
    return whole


def dropped(reader: Reader, heard: Said, before: Sequence[str], outcome: Outcome) -> Outcome:
    """ "The umbrella is mine, you can give to me?": a request that asks what thing (its thing left
    out) after clauses (`before`) that name one is about that thing, as "it" would be; else the
    outcome as it was."""
    if not outcome.clarify or outcome.open_role != "object" or not before:
        return outcome
    p = parse(reader.lang, heard, reader.robot_name)
    kinds = ROLE_KINDS.get(p.intent or "", {}).get("object")
    if p.act != "command" or p.slots.get("object") or kinds is None:
        return outcome
    ref = antecedent(reader.lexicon, before, kinds, speaker=reader.speaker)
    return outcome if ref is None else reader.act(p, {"object": tuple(tokens(ref.id))})


def wished(reader: Reader, heard: Said, before: Sequence[str], outcome: Outcome) -> Outcome:
    """ "I want the pear, can you get it", "Felix needs his glasses, could you grab them": a thing
    taken that an earlier clause or part (`before`) wished for is brought to whoever wished for it;
    so is one brought with no one said ("Mr Haddad would like the trowel, please bring it")."""
    taken = outcome.intent == I.GRAB_OBJECT or _brought_to_no_one_said(reader, heard, before, outcome)
    for i in range(len(before) - 1, -1, -1) if taken else ():
        p = parse(reader.lang, heard.of(before[i]), reader.robot_name)
        if p.act != "command" or p.intent != I.BRING_OBJECT:
            continue
        context = (*reader.history, *(Utterance(reader.speaker, c) for c in before[:i]))
        wish = reader.within(context).act(p)
        if wish.intent == I.BRING_OBJECT and wish.roles.get("object") == outcome.roles.get("object"):
            return wish
    return outcome


def _brought_to_no_one_said(reader: Reader, heard: Said, before: Sequence[str], outcome: Outcome) -> bool:
    """Whether the request after the clauses `before` brings a thing without saying to whom (the
    speaker only by default: "please bring it")."""
    if outcome.intent != I.BRING_OBJECT or outcome.roles.get("recipient") != reader.speaker or not before:
        return False
    at = heard.text.rfind(before[-1])
    p = parse(reader.lang, heard.of(heard.text[at + len(before[-1]) :]), reader.robot_name)
    said = p.slots.get("rest", ())
    return "recipient" not in p.slots and not set(said) & reader.lang.words.me


def _joins(before: Sequence[Outcome], outcome: Outcome) -> bool:
    """Whether a part engages with the very person the part before went to: the engaging is the
    request, and going to them is part of it."""
    went = before[0] if before else None
    return (went is not None and went.intent == I.MOVE_TO and outcome.intent == I.ENGAGE_WITH
            and went.roles.get("goal") == outcome.roles.get("recipient"))  # fmt: skip


def _unskilled(reader: Reader, part: Said) -> bool:
    """Whether a part asks for an activity the robot has no skill for ("... and wash it")."""
    return not skilled(reader.lang, parse(reader.lang, part, reader.robot_name))


def _asks(reader: Reader, part: Said) -> bool:
    """Whether a part asks a question about the situation ("tell me how many mugs there are")."""
    return parse(reader.lang, part, reader.robot_name).act == "question"


def _fetched_for(reader: Reader, done: list[Outcome], verbs: list[str | None]) -> list[Outcome]:
    """ "fetch the flask and then take it to Theo", "get the secateurs off the shelf and hand them to
    Margit": a thing fetched, then brought on to someone, is one bringing to them."""
    fetching = reader.lang.requests.compound.fetching
    out: list[Outcome] = []
    for i, o in enumerate(done):
        after = done[i + 1] if i + 1 < len(done) else None
        thing = o.roles.get("object")
        fetched = verbs[i] in fetching and o.intent in {I.GRAB_OBJECT, I.BRING_OBJECT}
        if not (fetched and after is not None and after.intent == I.BRING_OBJECT and thing is not None
                and after.roles.get("object") == thing):  # fmt: skip
            out.append(o)
    return out


def _taken_first(reader: Reader, done: list[Outcome]) -> list[Outcome]:
    """ "bring the mug and put it on the tray", "bring me the box and then take it to Ana": a thing
    brought to the speaker and then carried on elsewhere is taken first, not brought ("fetch the
    juice and give it to Amara" is one bringing already: `_fetched_for`)."""
    out = list(done)
    for i in range(len(out) - 1):
        first, after = out[i], out[i + 1]
        thing = first.roles.get("object")
        if first.intent != I.BRING_OBJECT or first.roles.get("recipient") != reader.speaker:
            continue
        entity = reader.snapshot.get(thing or "")
        if after.intent not in _HANDED_ON or after.roles.get("object") != thing or entity is None:
            continue
        roles = {"object": entity.id}
        reply = acknowledgement(reader.lang, reader.snapshot, reader.speaker, I.GRAB_OBJECT, roles,
                                {"object": Ref(entity)})  # fmt: skip
        out[i] = replace(first, intent=I.GRAB_OBJECT, roles=roles, reply=reply)
    return out
