"""The grammar of requests as data: verb frames.

A row says which verb phrases ask for an intent and how the words after the verb fill its roles:
the role of the words right after the verb (`direct`), the prepositions that introduce each other
role (`slots`, found in any order: "bring the tray to Ana" and "bring to Ana the tray"), the
particles dropped around them ("pick *up*", "head *over* to"), the role that a bare "here"/"there"
fills, and which roles must be said for the row to apply. Verbs are lemmas, so "picking", "took"
and "puts" need no row of their own; multi-word verbs ("get hold of", "make your way") are phrases.
What a row cannot say is a small function of dialogue.understanding.requests.constructions, named in the row.

Rows are tried longest verb phrase first, then in table order; the first that fits wins. To add a
verb, add it to a row (or add a row).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache
from typing import Literal

from dialogue import intents as I
from dialogue.reference.english import ME, Words, phrases, word_set
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse
from dialogue.understanding.requests import constructions as C
from dialogue.understanding.words import (
    ACTIVITY_FILLER,
    CARRY_PARTICLES,
    GOALS,
    MOTION_GOALS,
    MOTION_PARTICLES,
    NO_INTENT_VERBS,
    PLACES,
    STOP_FILLER,
)

#: How a row makes the free-form text of its intent from (verb, words after it).
Text = Callable[[str, Words], str | None]
Special = Callable[[C.Said], Parse | None]


def _named(name: str) -> Text:
    return lambda verb, rest: name


def _verb(verb: str, rest: Words) -> str:
    return verb


def _activity(verb: str, rest: Words) -> str | None:
    """ "play a game with me" -> "play_game"; "start (to) vacuum" -> "vacuum"."""
    words = rest[1:] if rest[:1] == ("to",) else rest
    words = words[: words.index("for")] if "for" in words[1:] else words  # ("story time for the little ones")
    return "_".join(w for w in words if w not in ACTIVITY_FILLER) or None


def _doing(verb: str, rest: Words) -> str | None:
    """ "water the plants" -> "water_plants": the verb names the activity."""
    return _activity(verb, (*verb.split(), *rest))


def _stopping(verb: str, rest: Words) -> str | None:
    return "_".join(w for w in rest if w not in STOP_FILLER) or None


@dataclass(frozen=True)
class Frame:
    #: Verb phrases ("grab|pick|get hold of"): the first word is a lemma, the others as said.
    verbs: str
    intent: str | None = None
    #: The role of the words right after the verb, with no preposition ("bring *the cup* to Ana").
    #: A role the intent does not ground ("extra", "manner") takes words that change nothing.
    direct: str | None = None
    #: Each other role and the prepositions that introduce it ("to|towards|for").
    slots: dict[str, str] = field(default_factory=dict)
    #: Words dropped next to the verb, at the end of a phrase or before a preposition.
    particles: str = ""
    #: The role a bare "here" (the speaker) or "there" (the place just spoken of) fills.
    here: str | None = None
    #: Only "there" fills it ("wait there": the place spoken of; "wait here" is to stay put).
    there_only: bool = False
    #: The direct words may start with the recipient: "me"/"us" only ("get me a cup"), anyone
    #: ("give Ines her phone": split against the KB by the interpreter), or anyone said before a
    #: noun phrase of its own ("get Ines her phone", but "get the phone").
    dative: Literal["me", "any", "before"] | None = None
    #: The only words the direct role may be ("take *me* to the kitchen").
    only: frozenset[str] | None = None
    #: Roles that must be said for the row to apply (else the next row is tried).
    requires: tuple[str, ...] = ()
    #: A role's value when it is not said (it is then marked implicit).
    defaults: dict[str, Words] = field(default_factory=dict)
    #: The verb phrase is all there is ("sleep"), not the start of a longer request.
    whole: bool = False
    text: Text | None = None
    #: A function for what the row cannot say; it returns None when it does not apply.
    special: Special | None = None
    #: "go (and) get the cup": a verb after this one is the request.
    serial: bool = False


_GRAB = "grab|take|get|collect|lift|grasp|seize|hold|pick"
_BRING = "bring|hand|give|pass|fetch|deliver|carry|wheel|push|drag|pull|slide|shift"
_THROW = "chuck|throw|toss|bung|lob"
_PLACE = f"put|place|set|lay|drop|leave|stick|stack|release|rest|hang|store|park|shove|dump|pop|{_THROW}"
_MOVE = (
    "go|move|navigate|drive|walk|head|come|return|proceed|roll|stand|pop|nip|hop|make your way|"
    "find your way"
)
_GUIDE = "guide|lead|escort|accompany|show|direct"
#: Verbs that only ever say where to go: "get over to the desk", "run to the kitchen" ("get the cup",
#: "run the dishwasher" are other rows').
_GO = "get|swing|hurry|rush|dash|wander|run|scoot|zip"
_STAY = "wait|stay|remain|hang on|hang about|hang around|sit"
_AT = "in|inside|at|by|near|beside|outside|on|under|behind"
#: "wait *out* in the courtyard", "stay *over* by the door", "wait *downstairs* in the hall"
_OUT = "out over back down up outside upstairs downstairs"
#: Particles of the way someone is taken: "show Ana *out* to the terrace", "walk me *back*".
_ALONG = "over back through out in up down round around along"
_SAY = "say|tell|announce|repeat|inform|remind|ask"
_TO_SOMEONE = "to|towards|for|into"

FRAMES: tuple[Frame, ...] = (
    # The robot itself.
    Frame("wake up", I.WAKEUP, direct="extra"),
    Frame("wake|wakeup", I.WAKEUP, whole=True),
    Frame("go to sleep|take a break", I.SUSPEND, direct="extra"),
    Frame("sleep|suspend|standby|stand by|rest|power down", I.SUSPEND, whole=True),
    Frame("stop|cancel|halt|abort|quit|cease|end|pause|interrupt|shut up|enough", I.STOP_ACTIVITY,
          direct="activity", text=_stopping),
    # People.
    Frame("greet", special=C.everyone),
    Frame("greet|welcome|say hello to|say hi to|wave hello to|wave hi to", I.GREET, direct="recipient"),
    # "this is Callum, say hello": the person just introduced (else the speaker)
    Frame("say hello|say hi|say hiya|wave hello|wave hi|say good morning|say good afternoon|"
          "say good evening", I.GREET, whole=True, defaults={"recipient": ("me",)}),
    Frame("look at|turn to|turn towards|face|engage with|talk to|talk with|speak to|speak with|"
          "interact with|interact to|engage to", I.ENGAGE_WITH, direct="recipient"),
    Frame("dance|wave|nod|bow|clap|point|spin|jump|salute", I.PERFORM_MOTION, direct="manner",
          slots={"recipient": "to|at"}, text=_verb),
    Frame("shake hands|shake", I.PERFORM_MOTION, direct="manner", slots={"recipient": "with|to|at"},
          text=_named("shake_hands")),
    Frame(_SAY, special=C.speech),
    Frame("let", special=C.letting_know),
    Frame("help", special=C.helping),
    Frame("give", special=C.a_hand),
    Frame("show", special=C.showing),
    # "show Noor (the) way to the exit": the way is no one's name; "show Ana out to the terrace",
    # "see Mr Ito up to his room": the particle says the way
    Frame(_GUIDE, I.GUIDE, direct="recipient", slots={"goal": "to|towards|into"}, here="goal",
          particles=f"way {_ALONG}", defaults={"recipient": ("me",)}),
    # "take me (there)": the place just spoken of ("I need the lifts, can you take me")
    Frame("take|walk", I.GUIDE, direct="recipient", slots={"goal": "to|towards|into"}, here="goal",
          particles=_ALONG, only=ME, defaults={"goal": ("there",)}),
    Frame("bring", I.GUIDE, direct="recipient", slots={"goal": "to|towards|into"}, here="goal",
          particles="over back through", only=ME, requires=("goal",)),
    # Going somewhere.
    Frame("go|come", serial=True),
    Frame("approach|enter|reach|visit", I.MOVE_TO, direct="goal", requires=("goal",)),
    # "come back", "come over": to the speaker
    Frame("come|come back|come over|come closer|come along", I.MOVE_TO, whole=True,
          defaults={"goal": ("me",)}),
    Frame(_MOVE, I.MOVE_TO, slots={"goal": MOTION_GOALS}, particles=MOTION_PARTICLES, here="goal",
          requires=("goal",)),
    # "go and wait in the courtyard", "stay by the door": be there ("wait for me" is no place)
    # ("go to the shed and wait there": the place just spoken of)
    # ("wait there for the van": what for changes nothing)
    Frame(_STAY, I.MOVE_TO, slots={"goal": _AT, "extra": "for|until|till"}, particles=f"there {_OUT}",
          here="goal", there_only=True, requires=("goal",)),
    Frame(_GO, I.MOVE_TO, slots={"goal": MOTION_GOALS}, particles=MOTION_PARTICLES, here="goal",
          requires=("goal",)),
    Frame(_MOVE, I.PLACE_OBJECT, direct="object", slots={"recipient": GOALS}, particles="back away down over",
          requires=("object", "recipient")),
    # Handing things out to everyone: no intent says it ("hand out the worksheets" is no bringing).
    Frame("hand out|give out|pass out|pass round|pass around|hand round|hand around|share out"),
    # Things.
    # "chuck me the remote", "throw the ball to me"; "chuck the rag in the sink" is the next row's
    Frame(_THROW, I.BRING_OBJECT, direct="object", slots={"recipient": "to"}, particles=CARRY_PARTICLES,
          dative="before", requires=("recipient",)),
    Frame(_PLACE, I.PLACE_OBJECT, direct="object", slots={"recipient": PLACES}, here="recipient",
          particles="down away back over out up"),
    Frame(_BRING, I.BRING_OBJECT, direct="object", slots={"recipient": _TO_SOMEONE}, here="recipient",
          particles=CARRY_PARTICLES, dative="any"),
    # "get me a cup", "take Ines her phone"
    Frame(_GRAB, I.BRING_OBJECT, direct="object", slots={"recipient": _TO_SOMEONE}, particles=CARRY_PARTICLES,
          dative="before", requires=("recipient",)),
    Frame(f"{_GRAB}|get hold of|take hold of|grab hold of|catch hold of", I.GRAB_OBJECT, direct="object",
          particles="up down out"),
    # Activities.
    Frame("do", special=C.asking),
    Frame("start|begin|launch|run|resume|do|perform|commence|kick off|get started with|get going with|"
          "crack on with|start off", I.START_ACTIVITY, direct="activity",
          text=_activity),
    Frame("clean|tidy|vacuum|hoover|sweep|mop|wash|dust|cook|water|iron|fold|patrol|charge|sing|exercise|"
          "wipe|organise|organize|prepare|make|cleaning|vacuuming|tidying|play", I.START_ACTIVITY,
          direct="activity", text=_doing),
)  # fmt: skip

#: What the whole utterance may say before any verb is read ("I'm parched", "I want the apple").
CONSTRUCTIONS: tuple[Special, ...] = (C.need, C.going, C.wanting, C.their_wish, C.belonging, C.enough)


@dataclass(frozen=True)
class Row:
    """A frame with its strings read into words (once, on first use)."""

    frame: Frame
    order: int
    particles: frozenset[str]
    slots: tuple[tuple[Words, str], ...]  # (preposition, role), longest preposition first


@cache
def verb_index(lang: Language) -> dict[str, tuple[tuple[Words, Row], ...]]:
    """First word of a verb phrase -> (phrase, row), longest phrase first, then in table order."""
    index: dict[str, list[tuple[Words, Row]]] = {}
    for order, frame in enumerate(FRAMES):
        slots = sorted(((p, role) for role, preps in frame.slots.items() for p in phrases(preps)),
                       key=lambda s: -len(s[0]))  # fmt: skip
        row = Row(frame, order, word_set(frame.particles), tuple(slots))
        for verb in phrases(frame.verbs):
            index.setdefault(verb[0], []).append((verb, row))
    return {w: tuple(sorted(rows, key=lambda r: (-len(r[0]), r[1].order))) for w, rows in index.items()}


@cache
def verbs(lang: Language) -> frozenset[str]:
    """Every word a request may start with (the first words of the table's verb phrases)."""
    return frozenset(verb_index(lang))


@cache
def known_verbs(lang: Language) -> frozenset[str]:
    """The table's verbs and the actions the robot has no intent for ("find", "open")."""
    return verbs(lang) | NO_INTENT_VERBS
