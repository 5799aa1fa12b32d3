"""Shared vocabulary of the rules grammar: normalisation, politeness, verb classes, phrase splitting.

Only function words and verbs live here; nouns always come from the KB (dialogue.reference.lexicon).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal

Act = Literal["command", "question", "greeting", "negated", "thanks", "unknown"]
Words = tuple[str, ...]

_TOKEN = re.compile(r"[a-z0-9]+(?:'[a-z]+)?")
QUOTED = re.compile(r"[\"\u201c\u201d]([^\"\u201c\u201d]+)[\"\u201c\u201d]")


def _phrases(text: str) -> tuple[Words, ...]:
    """ "a b|c" -> (("a", "b"), ("c",)): compact phrase lists."""
    return tuple(tuple(p.split()) for p in text.split("|"))


def word_set(text: str) -> frozenset[str]:
    return frozenset(text.split())


CONTRACTIONS: dict[str, Words] = {
    "what's": ("what", "is"), "where's": ("where", "is"), "who's": ("who", "is"), "that's": ("that", "is"),
    "it's": ("it", "is"), "there's": ("there", "is"), "let's": ("let", "us"), "i'd": ("i", "would"),
    "can't": ("cannot",), "i'm": ("i", "am"), "you're": ("you", "are"), "here's": ("here", "is"),
    "dont": ("don't",), "doesn't": ("don't",), "won't": ("don't",),
    # Speech recognisers and chat drop the apostrophe.
    "whats": ("what", "is"), "wheres": ("where", "is"), "whos": ("who", "is"), "thats": ("that", "is"),
    "theres": ("there", "is"), "heres": ("here", "is"), "shes": ("she", "is"), "hes": ("he", "is"),
    "im": ("i", "am"), "ive": ("i", "have"), "youre": ("you", "are"), "cant": ("cannot",),
    "doesnt": ("don't",), "wont": ("don't",), "isnt": ("is", "not"), "arent": ("are", "not"),
    "didnt": ("did", "not"), "i've": ("i", "have"), "she's": ("she", "is"), "he's": ("he", "is"),
    "we're": ("we", "are"), "they're": ("they", "are"), "hows": ("how", "is"),
}  # fmt: skip
#: Hesitations and discourse fillers, dropped wherever they occur ("put the uh candle on the table").
FILLERS = frozenset({"um", "umm", "uh", "uhh", "er", "erm", "hmm", "mm", "ah", "really"})
#: Two-word fillers dropped wherever they occur.
FILLER_PAIRS = frozenset({("you", "know"), ("i", "guess"), ("of", "course")})
#: Words of an answer that only add emphasis ("mine, obviously", "the red one definitely").
INTERJECTIONS = word_set(
    "obviously definitely clearly surely certainly naturally yes yeah yep sure please thanks"
)
#: A self-repair: what follows replaces the request said before it ("bring me the uh no wait put...").
REPAIRS = _phrases("no wait|wait no|sorry i mean|no sorry|i mean|or rather|no no|scratch that|no actually")
POLITE_PREFIXES = _phrases(
    "would you mind|do you mind|i would like you to|i want you to|i need you to|i wish you would|"
    "go ahead and|go and|come and|could you|can you|would you|will you|please|kindly|just|now|ok|okay|"
    "so|and|then|also|well|robot|let us|try to|you should|you can|you could|be so kind and|be so kind as to|"
    "time to|maybe|hold on|hang on|wait a moment|wait a second|one moment|actually|oh|um|umm|uh|er|erm|"
    "great|alright|all right|cool|perfect|excellent|sorry|excuse me|can we|could we|shall we|should we|"
    "why don't we|how about we|i was wondering if you could|i wonder if you could|"
    "i was wondering whether you could|"
    "be a dear and|be an angel and|do me a favour and|do me a favor and|you know what|off you|listen|"
    "would you be so kind as to|would you be able to|are you able to|if you could|if you can"
)
POLITE_SUFFIXES = _phrases(
    "please|thanks|thank you|now|right now|if you can|if you could|for a moment|again|quickly|"
    "immediately|ok|okay|would you|will you|could you|can you|won't you|for a sec|for a second"
)
GREETINGS = _phrases(
    "good morning|good afternoon|good evening|good day|hello|hi|hey|hiya|howdy|greetings|yo|"
    "hello there|hi there|hey there|welcome|morning|evening|afternoon"
)
SOCIAL = frozenset(
    _phrases(
        "nice to see you|nice to meet you|good to see you|glad to see you|how are you|how are you doing|"
        "how is it going|there|robot|everyone|again|friend||how do you do"
    )
)
ME = word_set("me myself us")
GRAB = word_set("grab take pick get collect lift grasp seize hold")
BRING = word_set("bring hand give pass fetch deliver carry")
PLACE = word_set("put place set lay drop leave stick stack")
MOVE = word_set("go move navigate drive walk head come return proceed roll stand pop nip hop")
GUIDE = word_set("guide lead escort accompany show direct")
SAY = word_set("say tell announce repeat inform remind")
START = word_set("start begin launch run resume do perform commence")
STOP = word_set("stop cancel halt abort quit cease end pause interrupt")
ACTIVITY_VERBS = word_set(
    "clean tidy vacuum hoover sweep mop wash dust cook water iron fold patrol charge sing exercise wipe "
    "organise organize prepare make cleaning vacuuming tidying play"
)
MOTIONS = word_set("dance wave nod bow clap point shake spin jump salute")
STOP_FILLER = word_set(
    "what you are doing it that this everything all the current activity task now please immediately "
    "right there your whatever am is enough shut up"
)
LOCATIVE = ("on top of", "onto", "on", "into", "inside", "in", "at", "to", "under", "next to", "near")
COLOURS = word_set(
    "red green blue yellow orange purple violet pink brown black white grey gray silver gold golden beige "
    "navy turquoise cyan magenta maroon cream tan teal"
)
WH = word_set("what where who which how why when whose whom")
#: "I'm parched": a need names the ontology class of what would meet it.
NEEDS: dict[str, str] = {
    "thirsty": "drink", "parched": "drink", "dehydrated": "drink",
    "hungry": "food", "starving": "food", "peckish": "food", "famished": "food", "ravenous": "food",
}  # fmt: skip
INTENSIFIERS = word_set("so very really absolutely quite a bit little totally getting rather pretty bloody")
_ASKING = word_set("do did don't if would as you that whether about him her them it")


@dataclass(frozen=True)
class Parse:
    act: Act
    intent: str | None = None
    slots: dict[str, Words] = field(default_factory=dict)
    text: str | None = None
    question: str | None = None
    words: Words = ()
    #: BRING/give without "to": the recipient and the object are both in `slots["rest"]`.
    double_object: bool = False


#: Every verb the grammar knows, to read "would you mind picking up..." as "pick up...".
VERBS = GRAB | BRING | PLACE | MOVE | GUIDE | SAY | START | STOP | MOTIONS
VERBS |= word_set("greet welcome approach enter")
#: Verbs that start a command (a part of a compound request starts with one of these).
COMMAND_VERBS = VERBS | ACTIVITY_VERBS
#: Actions the robot has no intent for: a part of a compound request with one of these is kept in
#: the reply ("I can't find the newspaper myself"), never silently dropped.
NO_INTENT_VERBS = word_set(
    "find search look open close turn switch remove control check wait stay watch heat boil pour fill "
    "empty plug unplug lock unlock answer call fix feed throw follow serve"
)


def base_verb(word: str) -> str:
    """ "picking" -> "pick", "taking" -> "take", "putting" -> "put"; other words unchanged."""
    if word in VERBS or not word.endswith("ing") or len(word) < 5:
        return word
    stem = word[:-3]
    for candidate in (stem, stem + "e", stem[:-1]):
        if candidate in VERBS:
            return candidate
    return word


def normalise(text: str) -> list[str]:
    """Lower-case words with contractions expanded, fillers and stutters removed and a self-repair
    applied ("put the put the knife uh on the table", "bring me the uh no wait put the candle...")."""
    words: list[str] = []
    for w in _TOKEN.findall(text.lower().replace("\u2019", "'")):
        words.extend(x for x in CONTRACTIONS.get(w, (w,)) if x not in FILLERS)
    return _repaired(_unrepeated(_without_filler_pairs(words)))


def _without_filler_pairs(words: list[str]) -> list[str]:
    """ "pick up the uh you know the cup": "you know" mid-sentence, but not "do you know where..."."""
    drop: set[int] = set()
    for i in range(1, len(words) - 1):
        nxt = words[i + 2] if i + 2 < len(words) else ""
        if (
            tuple(words[i : i + 2]) in FILLER_PAIRS
            and words[i - 1] not in _ASKING
            and nxt not in WH | _ASKING
        ):
            drop.update((i, i + 1))
    return [w for i, w in enumerate(words) if i not in drop]


def cleaned(text: str) -> str:
    """The text with stutters and self-repairs resolved, when it has any (else unchanged, so that
    quoted words and casing survive): what a compound request is cut in."""
    lowered = text.lower().replace("\u2019", "'")
    plain = [x for w in _TOKEN.findall(lowered) for x in CONTRACTIONS.get(w, (w,))]
    words = [w for w in plain if w not in FILLERS]
    fixed = _repaired(_unrepeated(words))
    return text if fixed == words else " ".join(fixed)


def _unrepeated(words: list[str]) -> list[str]:
    """ "put the put the knife", "the the jumper": an immediately repeated run of 1-3 words once."""
    out: list[str] = []
    for w in words:
        out.append(w)
        for n in (1, 2, 3):
            if len(out) >= 2 * n and out[-n:] == out[-2 * n : -n] and not out[-1].isdigit():
                del out[-n:]
                break
    return out


def _repaired(words: list[str]) -> list[str]:
    """After the last self-repair marker, a new request replaces the one before it."""
    for i in range(len(words) - 1, 0, -1):
        for marker in REPAIRS:
            if tuple(words[i : i + len(marker)]) == marker:
                after = words[i + len(marker) :]
                request = strip_politeness(after)
                if request and base_verb(request[0]) in VERBS:
                    return after
    return words


def original_text(text: str, words: Sequence[str]) -> str:
    """The part of the original text that the (normalised) words came from, with its casing."""
    lowered = text.lower().replace("\u2019", "'")
    if len(lowered) != len(text) or not words:
        return " ".join(words)
    spans = [
        (w, m.start(), m.end())
        for m in _TOKEN.finditer(lowered)
        for w in CONTRACTIONS.get(m.group(), (m.group(),))
    ]
    n = len(words)
    for i in range(len(spans) - n + 1):
        if all(spans[i + k][0] == words[k] for k in range(n)):
            return text[spans[i][1] : spans[i + n - 1][2]]
    return " ".join(words)


def starts(words: Sequence[str], prefix: Sequence[str]) -> bool:
    return len(prefix) <= len(words) and tuple(words[: len(prefix)]) == tuple(prefix)


def strip_politeness(words: list[str], robot_name: str = "") -> list[str]:
    name = tuple(normalise(robot_name)) if robot_name else ()
    prefixes = (*POLITE_PREFIXES, *((name,) if name else ()))
    changed = True
    while changed and words:
        changed = False
        for p in prefixes:
            # "can you see" is a question, not a polite request: keep it.
            if p and starts(words, p) and not (p[-1] == "you" and words[len(p) : len(p) + 1] == ["see"]):
                words = words[len(p) :]
                changed = True
                break
        for s in POLITE_SUFFIXES:
            if s and len(words) > len(s) and tuple(words[-len(s) :]) == s:
                words = words[: -len(s)]
                changed = True
                break
    return words


#: Words that never address someone by name at the start of an utterance.
_NOT_VOCATIVE = word_set(
    "i you we he she it they there this that these those do does did is are was can could would will "
    "shall should may might must please let what where who which how why when whose the a an my your "
    "his her our their no not yes if and or but so then me us him them"
)
#: Filler words at the start of an utterance ("listen, go to the kitchen").
_LEAD_FILLERS = word_set("listen look hey see")


def strip_vocative(words: list[str], robot_name: str = "") -> list[str]:
    """ "john can you go to the bathroom", "michael go to the kitchen": the addressee's name (one
    word before a request) is not part of the request."""
    while len(words) > 2 and words[0] in _LEAD_FILLERS and base_verb(words[1]) in COMMAND_VERBS:
        words = words[1:]
    if len(words) < 3 or words[0] in _NOT_VOCATIVE or words[0] in COMMAND_VERBS or not words[0].isalpha():
        return words
    polite = any(starts(words[1:], p) and p[-1:] == ("you",) for p in POLITE_PREFIXES)
    if polite or base_verb(words[1]) in COMMAND_VERBS:
        return strip_politeness(words[1:], robot_name)
    return words


def split_at(words: Sequence[str], separators: Sequence[str]) -> tuple[Words, str, Words] | None:
    """First occurrence (after position 0) of any separator phrase: (before, separator, after)."""
    seps = [tuple(s.split()) for s in separators]
    for i in range(1, len(words)):
        for sep in seps:
            if tuple(words[i : i + len(sep)]) == sep:
                return tuple(words[:i]), " ".join(sep), tuple(words[i + len(sep) :])
    return None
