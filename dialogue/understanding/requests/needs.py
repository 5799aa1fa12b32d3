"""Needs said before any verb ("I'm parched", "we are starving", "Ruby's thirsty, is there any
lemonade?", "Freya's after her goggles"): something of the class that meets the need, or the thing
said, brought to whoever has it; and a thing said to need a chore ("the parcel needs taking to Lars")."""

from __future__ import annotations

from dialogue import intents as I
from dialogue.reference.english import Words
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse
from dialogue.understanding.requests.constructions import ConstructionGrammar, Framed


def need(said: Framed) -> Parse | None:
    """ "I'm really parched", "we are starving": something of the class that meets the need."""
    c = said.lang.derived(ConstructionGrammar)
    w = said.words
    whose: Words = ("me",)
    needy = next((n for n in c.needy if w[: len(n)] == n), None)
    if needy is not None:
        w = w[len(needy) :]
    elif _someone(c, w[:1]) and w[1:2] in c.someone_is:  # "Ruby is thirsty"
        whose, w = w[:1], w[2:]
    elif w[:1] and w[0].endswith("'s") and _someone(c, (w[0].removesuffix("'s"),)):  # "Ruby's thirsty"
        whose, w = (w[0].removesuffix("'s"),), w[1:]
    else:
        return _anything_for(said, c, w)
    rest = [x for x in w if x not in c.intensifiers]
    wanted = c.needs.get(rest[0]) if rest else None
    if wanted is None:
        return None
    if len(rest) == 1:  # (of someone else, a remark: what to bring them is asked for after it)
        return said.command(I.BRING_OBJECT, object=(wanted,), recipient=whose) if whose == ("me",) else None
    asked = _available(c, tuple(rest[1:]))  # "I'm parched, any tea going?": the tea
    if whose != ("me",) and asked[-2:-1] in c.for_whom and asked[-1] in c.personal:
        asked = asked[:-2]  # ("is there any lemonade for her?": for whoever is thirsty)
    at = next((i for i, x in enumerate(rest) if x in c.anything), 0)
    if not asked and at and set(rest[1:at]) <= c.asking:  # ("I'm thirsty, got anything sugar free?")
        asked = tuple(rest[at:])
    if asked[:1] and asked[0] in c.anything:  # "is there anything to eat": what meets the need
        asked = (*_qualifiers(said, asked[1:]), wanted)  # (of it, "anything sugar free": those)
    if set(asked) & c.function_words:
        return None
    return said.command(I.BRING_OBJECT, object=asked, recipient=whose) if asked else None


def _anything_for(said: Framed, c: ConstructionGrammar, w: Words) -> Parse | None:
    """ "is there anything to eat": what meets the need its purpose says, brought to the speaker."""
    asked = _available(c, w)
    wanted = said.lang.requests.purpose(asked[1:3]) if asked[:1] and asked[0] in c.anything else None
    if wanted is None or asked[3:]:
        return None
    return said.command(I.BRING_OBJECT, object=wanted, recipient=("me",))


def _someone(c: ConstructionGrammar, words: Words) -> bool:
    """Whether a word alone may be who has a need ("Ruby"): no function word."""
    return len(words) == 1 and words[0] not in c.function_words


def _qualifiers(said: Framed, words: Words) -> Words:
    """The words that say which of what meets a need is asked for ("sugar free" of "anything sugar
    free to drink"), without the purpose after them ("to drink")."""
    requests = said.lang.requests
    at = next((i for i in range(len(words)) if requests.purpose(words[i:]) is not None), len(words))
    return words[:at]


def _available(c: ConstructionGrammar, words: Words) -> Words:
    """What a question of what there is asks about ("is there any juice", "any tea going"); ()
    when the words are no such question."""
    lead = next((a for a in c.available if words[: len(a)] == a), None)
    if lead is None:
        return ()
    asked = words[len(lead) :]
    while asked and asked[-1] in c.available_ends:
        asked = asked[:-1]
    return asked


def chore_needed(lang: Language, words: Words) -> Words | None:
    """ "the kickboard needs putting back on the shelf": the chore as a request ("putting the
    kickboard back on the shelf"), the thing after its verb; None when the words say no such need."""
    c = lang.derived(ConstructionGrammar)
    if not words or words[0] not in c.np_start:
        return None
    at = next((i for i, w in enumerate(words) if w in c.needs_doing), None)
    if at is None or at + 1 >= len(words) or not c.doing or not words[at + 1].endswith(c.doing):
        return None
    if set(words[1:at]) & c.function_words:
        return None  # "the man with the parcel needs..." is said of someone, not a thing
    return (words[at + 1], *words[:at], *words[at + 2 :])


def their_pursuit(said: Framed) -> Parse | None:
    """ "Freya's after her goggles": the goggles, brought to Freya; of "a drink, the cola I
    reckon", the thing said last ("the cola")."""
    c = said.lang.derived(ConstructionGrammar)
    w = said.words
    if len(w) < 3 or not w[0].endswith("'s") or w[1] not in c.after:
        return None
    who = (w[0].removesuffix("'s"),)
    if not _someone(c, who):
        return None
    asked = w[2:]
    while (end := next((e for e in c.after_ends if len(asked) > len(e) and asked[-len(e) :] == e), None)):
        asked = asked[: -len(end)]
    last = max((i for i, x in enumerate(asked) if i and x in c.np_start), default=0)
    return said.command(I.BRING_OBJECT, object=asked[last:], recipient=who)
