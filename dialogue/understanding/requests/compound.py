"""Compound requests: one utterance, several commands in order ("go to the kitchen and take the plate").

An utterance is cut at "and", "then", "after that" or a comma when what follows starts with a verb
of the grammar, and before an imperative verb that starts a new command without any conjunction
("go to the bathroom take the rag"). Words only: what each part means is decided by the interpreter.
"""

from __future__ import annotations

from dataclasses import dataclass

from dialogue.reference.english import Words, phrases, spans, word_set
from dialogue.reference.resolution import content_words
from dialogue.understanding.language import Language
from dialogue.understanding.requests.frames import verbs
from dialogue.understanding.speech.plain import QUOTED, starts, strip_politeness
from dialogue.understanding.speech.repair import asked_verb, normalise, strip_vocative
from dialogue.understanding.words import AWAY, CHAT, GREETINGS, NO_INTENT_VERBS, RESULTS

_CONJUNCTIONS = word_set("and then , ; afterwards")
#: Verbs that start a new command even with no conjunction before them, when followed by one of
#: `_OBJECT_START` ("go to the bathroom take the rag"): never nouns in a command's phrases.
_BARE_VERBS = word_set(
    "take bring go put place grab fetch get find search give open move tell ask remind greet carry guide"
)
_SERIAL = word_set("go come")
#: A greeting asked for starts a request of its own, whatever came before it ("Agnes is here say hi").
_GREETING = frozenset(phrases("say hello|say hi|say hiya|say goodbye|say bye|wave hello|wave hi"))


def _greeting_at(toks: list[tuple[str, int, int]], i: int) -> bool:
    return i + 1 < len(toks) and (toks[i][0], toks[i + 1][0]) in _GREETING
_OBJECT_START = word_set(
    "the a an my your his her this that these those it them me us him to into some all both"
)
#: Words after which a verb continues the same command ("you take", "to take", "go get"), besides
#: the verbs of the grammar.
_NO_CUT_AFTER = word_set(
    "to you i we and then please can could would will go come let just also should must not don't never "
    "us me robot or but if when while before after so and the a an my your his her this that some "
    # after a modal or a negation a verb is that clause's own ("she can't find her keys")
    "cannot can't cant couldn't couldnt won't wont wouldn't wouldnt shouldn't don't dont doesn't doesnt "
    "didn't didnt do does did might may shall"
)


@dataclass(frozen=True)
class Part:
    text: str
    #: The verb the part starts with (None for a preamble such as "thanks" or "hello").
    verb: str | None
    #: The part's verb is one the robot has no intent for ("find", "turn on"), see NO_INTENT_VERBS.
    no_intent: bool
    #: The part only says where not to be ("move out of the way and go to the door"): what the
    #: parts after it do.
    aside: bool = False


def _verb(lang: Language, text: str) -> str | None:
    words = strip_politeness(lang, normalise(lang, text))
    for greeting in GREETINGS:  # "hey robot take the book"
        if starts(words, greeting) and len(words) > len(greeting):
            words = strip_politeness(lang, words[len(greeting) :])
            break
    words = strip_vocative(lang, words)
    if not words:
        return None
    return asked_verb(lang, words[0])


def conjuncts(lang: Language, text: str) -> list[Part]:  # noqa: C901
    """The commands of a compound request in order, or [] when the text is one request."""
    if QUOTED.search(text):  # "say 'stop and wait' to Tom": the quote is one text
        return []
    # (a conjunction as chat writes it: "get my bag n bring it over")
    toks = [(_one_word(word), start, end) for word, start, end in spans(text, marks=True)]
    no_cut_after = _NO_CUT_AFTER | verbs(lang) | _CONJUNCTIONS
    cuts: list[tuple[int, int]] = []  # (index of the first word of the new part, index after the cut)
    for i, (word, _, _) in enumerate(toks):
        if i == 0:
            continue
        if word in _CONJUNCTIONS:
            j = i
            while j < len(toks) and toks[j][0] in _CONJUNCTIONS:
                j += 1
            if j < len(toks) and (not cuts or cuts[-1][1] <= i):
                cuts.append((i, j))
        elif _greeting_at(toks, i) and toks[i - 1][0] not in no_cut_after:
            cuts.append((i, i))  # "Agnes is here say hi"
        elif word in _BARE_VERBS and toks[i - 1][0] not in no_cut_after:
            nxt = toks[i + 1][0] if i + 1 < len(toks) else ""
            # "...he is at the door go say hi to him": "go" or "come" before a verb starts a request too
            serial = word in _SERIAL and asked_verb(lang, nxt) in verbs(lang)
            if nxt in _OBJECT_START or serial:
                cuts.append((i, i))
    if not cuts:
        return []
    ranges: list[tuple[int, int]] = []  # token ranges of the parts
    start = 0
    for end, resume in cuts:
        ranges.append((start, end))
        start = resume
    ranges.append((start, len(toks)))
    parts: list[tuple[int, int]] = []
    for s, e in ranges:
        if s >= e:
            continue
        piece = text[toks[s][1] : toks[e - 1][2]]
        if parts and _verb(lang, piece) is None:  # "the cereals and the milk": not a new command
            parts[-1] = (parts[-1][0], e)
        else:
            parts.append((s, e))
    if len(parts) < 2:
        return []
    out = []
    for s, e in parts:
        piece = text[toks[s][1] : toks[e - 1][2]].strip(" ,;")
        verb = _verb(lang, piece)
        # ("go to the x-ray room and get it ready": no intent says the getting ready)
        said = normalise(lang, piece)
        result = verb is not None and bool(said) and said[-1] in RESULTS
        out.append(Part(piece, verb, verb in NO_INTENT_VERBS or result, _away(lang, piece)))
    return out


def _away(lang: Language, text: str) -> bool:
    """Whether a request only says where not to be ("get out of the way", "move out of my way")."""
    words = strip_vocative(lang, strip_politeness(lang, normalise(lang, text)))
    rest = tuple(w for w in words[1:] if w not in _A_BIT)
    return bool(words) and asked_verb(lang, words[0]) in verbs(lang) and rest in AWAY


_A_BIT = word_set("a bit little")


def _one_word(word: str) -> str:
    """The conjunction a chat abbreviation stands for ("n" for "and"), else the word as written."""
    said = CHAT.get(word, (word,))
    return said[0] if len(said) == 1 and said[0] in _CONJUNCTIONS else word


def alternatives(lang: Language, words: Words) -> list[Words]:
    """ "an apple or an orange" -> ["an apple", "an orange"]; [] without "or"."""
    if "or" not in words:
        return []
    out: list[Words] = [()]
    for w in words:
        if w == "or":
            out.append(())
        else:
            out[-1] = (*out[-1], w)
    return out if all(content_words(lang, t) for t in out) else []


def coordinated(lang: Language, words: Words) -> list[Words]:
    """ "the cereals and the milk" -> ["the cereals", "the milk"]; [] when there is no "and"."""
    if "and" not in words:
        return []
    out: list[Words] = []
    current: list[str] = []
    for w in words:
        if w == "and":
            out.append(tuple(current))
            current = []
        else:
            current.append(w)
    out.append(tuple(current))
    return out if all(content_words(lang, t) for t in out) else []


def unprefixed(reply: str) -> str:
    """ "OK, I will pick up the plate." -> "I will pick up the plate." """
    rest = reply.removeprefix("OK, ").removeprefix("OK: ")
    return rest[:1].upper() + rest[1:] if rest == reply else rest
