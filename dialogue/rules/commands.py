"""A small English grammar of robot commands, on whole words (D11).

This module only looks at words: it returns a `Parse` whose slots are still phrases. Which entity a
phrase names is decided later against the KB (dialogue.rules.interpret), so no noun is hard-coded here.
"""

from __future__ import annotations

from typing import Protocol

from dialogue import intents as I
from dialogue.rules.questions import question as _question
from dialogue.rules.words import (
    ACTIVITY_VERBS,
    BRING,
    GRAB,
    GREETINGS,
    GUIDE,
    INTENSIFIERS,
    LOCATIVE,
    ME,
    MOTIONS,
    MOVE,
    NEEDS,
    PLACE,
    QUOTED,
    SAY,
    SOCIAL,
    START,
    STOP,
    STOP_FILLER,
    Parse,
    Words,
    base_verb,
    normalise,
    original_text,
    split_at,
    starts,
    strip_politeness,
    strip_vocative,
    word_set,
)  # fmt: skip

__all__ = ["LOCATIVE", "ME", "Parse", "Words", "parse"]

_EVERYONE = frozenset({("everyone",), ("everybody",), ("all",), ("them", "all"), ("people",)})
#: Verbs that may follow "go"/"come" ("go greet Maria", "come pick up the cup").
_ERRAND_VERBS = GRAB | BRING | PLACE | SAY | {"greet", "check", "clean", "see"}
#: "I want X" and friends ask for X to be brought.
_WANTS: tuple[Words, ...] = tuple(
    tuple(p.split()) for p in ("i want", "i need", "i would like", "can i have", "could i have", "may i have",
                               "can i get", "could i get", "i will have", "give me", "i could use",
                               "i could do with", "i would love", "i would really like")
)  # fmt: skip
_GOAL_MARKERS = (
    "to", "towards", "into", "inside", "onto", "on", "in", "near", "next to", "over to", "by", "beside"
)  # fmt: skip
#: Words between a motion verb and its goal: "go back to", "head over to", "go down to the cellar".
_PARTICLES = word_set(
    "back over there straight right down up ahead across along out around round on and stand wait close "
    "closer quickly slowly carefully quietly safely directly"
)
_WANT_VERBS = word_set("want wants need needs")
#: What follows "do" in a request ("do the dishes", "do some exercise"); anything else after "do"
#: is a yes/no question ("do you like music", "do robots ever get tired").
_DONE = word_set("the a an some my your our this that these those exercise exercises yoga stretches")


class _Cmd(Protocol):
    def __call__(
        self, intent: str, text: str | None = None, double: bool = False, **slots: Words
    ) -> Parse: ...


def parse(text: str, robot_name: str = "") -> Parse:
    words = strip_vocative(strip_politeness(normalise(text), robot_name), robot_name)
    if not words:
        return Parse("unknown", words=())
    words[0] = base_verb(words[0])  # "(would you mind) picking up the cup"
    if words[0] == "no" and len(words) > 1 and words[1] not in {"need", "more", "thanks", "thank"}:
        words = strip_politeness(words[1:], robot_name)
    if words and (words[0] in {"don't", "never", "no"} or starts(words, ["do", "not"])):
        return Parse("negated", words=tuple(words))
    if not words:
        return Parse("unknown", words=())
    if words[0] in {"thanks", "thank"} or words == ["cheers"]:
        # "thanks, now put it on the shelf": the thanks is a preamble to the request
        tail = strip_politeness(words[2:] if words[:2] == ["thank", "you"] else words[1:], robot_name)
        return _request(text, tail) or Parse("thanks", words=tuple(words))
    if tuple(words) in SOCIAL and words[:1] != ["how"]:
        return Parse("greeting", words=tuple(words))
    # "welcome Lucia" asks the robot to greet her; "welcome back" is a greeting.
    welcoming = words[0] == "welcome" and words[1:] and words[1] not in {"back", "home", "to", "everyone"}
    for g in () if welcoming else sorted(GREETINGS, key=len, reverse=True):
        if starts(words, g):
            rest = strip_vocative(strip_politeness(words[len(g) :], robot_name), robot_name)
            if tuple(rest) in SOCIAL:
                return Parse("greeting", words=tuple(words))
            # "Good morning Maria" is still a greeting; "hi, grab the cup" is a request.
            return _request(text, rest) or Parse("greeting", words=tuple(words))
    return _question(words) or _command(text, words)


def _request(text: str, words: list[str]) -> Parse | None:
    """What follows a greeting or thanks, if it is a question or command."""
    if not words:
        return None
    after = _question(words) or _command(text, words)
    return after if after.act != "unknown" else None


#: Two-word prepositions read as one, so that their "to" is never taken for a recipient's.
_PREPOSITIONS = {("next", "to"): "beside", ("close", "to"): "near", ("nearest", "to"): "near"}


def _command(original: str, words: list[str]) -> Parse:
    for i in range(len(words) - 2, 0, -1):
        if (words[i], words[i + 1]) in _PREPOSITIONS:
            words[i : i + 2] = [_PREPOSITIONS[(words[i], words[i + 1])]]
    if words[:3] == ["make", "your", "way"] or words[:3] == ["find", "your", "way"]:
        words = ["go", *words[3:]]
    if words[1:3] == ["hold", "of"] and words[0] in GRAB | {"catch"}:  # "get hold of the mug"
        words = ["grab", *words[3:]]
    verb, rest = words[0], tuple(words[1:])
    w = tuple(words)

    def cmd(intent: str, text: str | None = None, double: bool = False, **slots: Words) -> Parse:
        return Parse("command", intent, dict(slots), text=text, words=w, double_object=double)

    need = _need(w)
    if need is not None:  # "I'm parched": something to drink
        return cmd(I.BRING_OBJECT, object=(need,), recipient=("me",))
    if verb == "help" and "to" in rest:  # "help me get to the bathroom": take them there
        who, _, goal = split_at(rest, ["get to", "to"]) or ((), "", ())
        if who and goal:
            return cmd(I.GUIDE, recipient=who, goal=goal)
    going = _wants_to_go(w)
    if going is not None:  # "Ellen needs to get to the utility room": take her there
        return cmd(I.GUIDE, recipient=going[0], goal=going[1])
    for lead in _WANTS:
        if starts(w, lead) and len(w) > len(lead):
            wanted = w[len(lead) :]
            if wanted[:3] == ("to", "go", "to"):  # "I want to go to the kitchen": take them there
                return cmd(I.GUIDE, recipient=("me",), goal=wanted[3:])
            if wanted[:1] != ("to",):  # "I would like the apple"
                return _bring("bring", ("me", *wanted), cmd)
    if verb in {"go", "come"} and rest[:1] and rest[0] in _ERRAND_VERBS:  # "go greet Maria"
        return _command(original, list(rest))
    if verb == "let" and "know" in rest:  # "let Tom know that..." is "tell Tom that..."
        return _say(original, "tell", tuple(x for x in rest if x != "know"), cmd)
    if verb in {"approach", "enter"} and rest:
        return cmd(I.MOVE_TO, goal=rest)
    if w[:2] in {("look", "at"), ("turn", "to"), ("turn", "towards")} or verb == "face":
        return cmd(I.ENGAGE_WITH, recipient=rest[1:] if verb != "face" else rest)
    if w[:2] == ("wake", "up") or w in {("wake",), ("wakeup",)}:
        return cmd(I.WAKEUP)
    if w[:3] in {("go", "to", "sleep"), ("take", "a", "break")} or w in {
        ("sleep",),
        ("suspend",),
        ("standby",),
        ("stand", "by"),
        ("rest",),
        ("power", "down"),
    }:
        return cmd(I.SUSPEND)
    enough = w[:2] == ("shut", "up") or (w[:2] == ("that", "is") and "enough" in w) or w == ("enough",)
    if verb in STOP or enough:
        activity = tuple(x for x in rest if x not in STOP_FILLER)
        return cmd(I.STOP_ACTIVITY, text="_".join(activity) or None)
    if verb == "greet" and rest in _EVERYONE:
        return Parse("greeting", words=w, slots={"everyone": rest})
    greeting_verb = verb in {"greet", "welcome"}
    if greeting_verb or (verb in {"say", "wave"} and rest[:2] in {("hello", "to"), ("hi", "to")}):
        recipient = rest if greeting_verb else rest[2:]
        if recipient[-2:] in {("for", "me"), ("from", "me"), ("for", "us"), ("from", "us")}:
            recipient = recipient[:-2]  # "say hi to Ahmed for me": still Ahmed
        return cmd(I.GREET, recipient=recipient)
    if verb in {"engage", "talk", "speak", "interact"} and rest[:1] in {("with",), ("to",)}:
        return cmd(I.ENGAGE_WITH, recipient=rest[1:])
    if verb in MOTIONS:
        found = split_at(("x", *rest), ["to", "at", "for"])
        target = found[2] if found and found[1] in {"to", "at"} else ()
        motion = verb if verb != "shake" else "shake_hands"
        return cmd(I.PERFORM_MOTION, text=motion, recipient=target)
    if verb in SAY:
        return _say(original, verb, rest, cmd)
    if verb in GUIDE or (verb in {"take", "walk", "bring"} and rest[:1] and rest[0] in ME and "to" in rest):
        if verb == "show" and "way" not in rest and "to" not in rest:
            thing = rest[1:] if rest[:1] and rest[0] in ME else rest
            return Parse("question", question="where", slots={"thing": thing}, words=w)
        if "way" in rest:
            rest = tuple(x for x in rest if x not in {"the", "way"})
        found = split_at(rest, ["to", "towards", "into"]) if rest[:1] != ("to",) else ((), "to", rest[1:])
        if found is None:
            return cmd(I.GUIDE, recipient=rest)
        return cmd(I.GUIDE, recipient=found[0] or ("me",), goal=found[2])
    if verb in MOVE:
        if rest in {("up",), ("back",), ("down",)}:
            return Parse("unknown", words=w)
        found = split_at(("x", *rest), _GOAL_MARKERS)
        if rest in {("here",), ("over", "here"), ("closer",), ("back", "here")}:
            return cmd(I.MOVE_TO, goal=("me",))
        if rest in {("there",), ("over", "there")}:
            return cmd(I.MOVE_TO, goal=("there",))
        if found is None:
            return Parse("unknown", words=w)
        if found[0] == ("x",) or set(found[0][1:]) <= _PARTICLES:
            return cmd(I.MOVE_TO, goal=found[2])
        return cmd(I.PLACE_OBJECT, object=found[0][1:], recipient=found[2])
    if verb in PLACE:
        found = split_at(rest, LOCATIVE)
        if found is None and rest[-1:] in {("there",), ("here",)} and len(rest) > 1:  # "put it over there"
            obj = tuple(x for x in rest[:-1] if x not in {"down", "away", "back", "over"})
            return cmd(I.PLACE_OBJECT, object=obj, recipient=("there",) if rest[-1] == "there" else ("me",))
        if found is None:
            obj = tuple(x for x in rest if x not in {"down", "away", "back"})
            return cmd(I.PLACE_OBJECT, object=obj, recipient=())
        obj = tuple(x for x in found[0] if x not in {"down", "away", "back"})
        return cmd(I.PLACE_OBJECT, object=obj, recipient=found[2])
    if verb in BRING or (
        verb in GRAB
        and (
            (verb != "pick" and rest[:1] and rest[0] in ME)
            or "to" in rest
            or rest[-2:] in {("for", "me"), ("for", "us")}
        )
    ):
        return _bring(verb, rest, cmd)
    if verb in GRAB:
        obj = rest
        if verb == "pick":
            obj = tuple(x for x in rest if x != "up")
        elif obj[-1:] == ("up",):
            obj = obj[:-1]
        return cmd(I.GRAB_OBJECT, object=obj)
    if verb in {"does", "did"} or (verb == "do" and rest[:1] and rest[0] not in _DONE):
        return Parse("unknown", words=w)  # "do you like music": a yes/no question, not an activity
    if verb in START or verb in ACTIVITY_VERBS:
        activity = rest if verb in START else w
        if verb in START and rest[:1] and rest[0] in {"to"}:
            activity = rest[1:]
        name = "_".join(x for x in activity if x not in {"the", "a", "an", "some", "with", "me", "us", "of"})
        return cmd(I.START_ACTIVITY, text=name or None)
    return Parse("unknown", words=w)


def _need(w: Words) -> str | None:
    """ "I'm absolutely parched", "we are starving": the class of what would meet the need."""
    if w[:2] not in {("i", "am"), ("we", "are")}:
        return None
    rest = [x for x in w[2:] if x not in INTENSIFIERS]
    return NEEDS.get(rest[0]) if len(rest) == 1 else None


def _wants_to_go(w: Words) -> tuple[Words, Words] | None:
    """ "I want to go to X", "Ellen needs to get to X": (who, where)."""
    for i in range(len(w) - 4):
        wants = w[i] in _WANT_VERBS or w[i : i + 2] in {("would", "like"), ("has", "to"), ("have", "to")}
        at = i + (2 if w[i] == "would" else 1)
        going = w[at : at + 1] == ("to",) and w[at + 1 : at + 2] in {("go",), ("get",)}
        if wants and going and w[at + 2 : at + 3] == ("to",) and w[at + 3 :]:
            who = w[:i]
            return (("me",) if who in {(), ("i",), ("we",)} else who), w[at + 3 :]
    return None


def _say(original: str, verb: str, rest: Words, cmd: _Cmd) -> Parse:
    quoted = QUOTED.search(original)
    if quoted:
        # The quoted words are the text; the recipient is found outside the quotes only.
        outside = normalise(original[: quoted.start()] + " " + original[quoted.end() :])
        rest = tuple(outside[outside.index(verb) + 1 :]) if verb in outside else ()
        rest = tuple(x for x in rest if x not in {"that", "please"})
        recipient = rest[1:] if rest[:1] == ("to",) else rest
        return cmd(I.SAY, text=quoted.group(1).strip(), recipient=recipient)
    if rest[:1] and rest[0] in {"goodbye", "bye"} and "to" in rest:
        return cmd(I.SAY, text="goodbye", recipient=rest[rest.index("to") + 1 :])
    if verb in {"tell", "inform", "remind"}:
        found = split_at(rest, ["that", "to", "about"])
        if found is not None:
            recipient, sep, text = found
            text = ("please", *text) if sep == "to" else text
            if sep == "about":
                return Parse("unknown", words=(verb, *rest))
        else:
            recipient, text = rest[:1], rest[1:]
        if recipient[:1] and recipient[0] in ME:  # "tell me a joke": small talk, not a SAY intent
            return Parse("unknown", words=(verb, *rest))
        if not text:  # "tell Maria": the interpreter asks what to say
            return cmd(I.SAY, recipient=recipient)
        said = original_text(original, text[1:] if text[0] == "please" else text)
        return cmd(I.SAY, text=f"please {said}" if text[0] == "please" else said, recipient=recipient)
    found = split_at(rest, ["to"])
    text_words, recipient = (found[0], found[2]) if found is not None else (rest, ())
    if not text_words:
        return Parse("unknown", words=(verb, *rest))
    return cmd(I.SAY, text=original_text(original, text_words), recipient=recipient)


def _bring(verb: str, rest: Words, cmd: _Cmd) -> Parse:
    dropped = {"over", "back", "up", "down", "along", "round", "around"}
    rest = tuple(x for x in rest if x not in dropped)
    if rest[-2:] in {("for", "me"), ("for", "us")}:
        return cmd(I.BRING_OBJECT, object=rest[:-2], recipient=("me",))
    if rest[-1:] == ("here",):
        return cmd(I.BRING_OBJECT, object=rest[:-1], recipient=("me",))
    found = split_at(rest, ["to", "towards", "for"])
    if found is not None:
        return cmd(I.BRING_OBJECT, object=found[0], recipient=found[2])
    if rest[:1] and rest[0] in ME:
        return cmd(I.BRING_OBJECT, object=rest[1:], recipient=("me",))
    return cmd(I.BRING_OBJECT, double=True, rest=rest)
