"""Questions about the situation ("what do you see", "where is X"...), on whole words.

The result is a `Parse` with `act="question"`, a question kind and the phrase it is about; the
answer is computed from the KB snapshot in dialogue.answers.
"""

from __future__ import annotations

from dialogue.words import WH, Parse, Words, split_at, starts, word_set

_SEES: tuple[Words, ...] = tuple(
    tuple(p.split()) for p in ("do you see", "can you see", "could you see", "have you seen", "did you see",
                               "are you seeing", "do you have", "is there", "are there")
)  # fmt: skip
_WHERE_LEADS: tuple[Words, ...] = tuple(
    tuple(p.split()) for p in ("is", "are", "can i find", "did you see", "did i put", "do you see", "was",
                               "were", "have you seen", "did i leave", "should i look for")
)  # fmt: skip
_ON_GLUE = word_set("is are do you see can lying there objects things thing stuff placed sitting kept")
_WHO_NOT_A_NAME = word_set("here there around in with present speaking talking at near next else")
_SEE_WORDS = frozenset({"see", "notice", "around", "front", "here", "there"})
_COLOUR_WORDS = frozenset({"colour", "color"})
_LOCATIVES = ("on top of", "on", "in", "inside", "under", "at")


def _q(kind: str, w: Words, **slots: Words) -> Parse:
    return Parse("question", question=kind, slots=dict(slots), words=w)


def _strip_ends(thing: Words, lead: frozenset[str], tail: frozenset[str]) -> Words:
    while thing[:1] and thing[0] in lead:
        thing = thing[1:]
    while thing[-1:] and thing[-1] in tail:
        thing = thing[:-1]
    return thing


def question(words: list[str]) -> Parse | None:
    w = tuple(words)
    if w[:2] in {("tell", "me"), ("show", "me")} and len(w) > 2 and w[2] in WH | {"about"}:
        if w[2] == "about":
            return _q("what_is", w, thing=w[3:])
        w = w[2:]
    head = w[:1]
    if head in {("what",), ("which",)}:
        return _what(w)
    if head == ("who",):
        if "you" in w and "are" in w and "see" not in w:
            return _q("name", w)
        if w[1:2] == ("is",) and w[2:] and w[2] not in _WHO_NOT_A_NAME:
            return _q("what_is", w, thing=w[2:])
        return _q("who_see", w)
    if head == ("where",):
        return _where(w)
    if starts(w, ("do", "you", "know", "where")):
        return _q("where", w, thing=_strip_ends(w[4:], frozenset({"is", "are"}), frozenset({"is", "are"})))
    if starts(w, ("how", "many")):
        thing = tuple(x for x in w[2:] if x not in {"do", "you", "see", "can", "are", "there", "is"})
        return _q("how_many", w, thing=thing)
    for lead in _SEES:
        if starts(w, lead):
            return _q("can_see", w, thing=w[len(lead) :])
    if head in {("is",), ("are",)} and len(w) > 2 and w[-1] in {"here", "there", "around", "present"}:
        return _q("can_see", w, thing=w[1:-1])  # "is Maria here?"
    if head in {("is",), ("are",)} and split_at(w, _LOCATIVES) is not None:
        return _q("can_see", w, thing=w[1:])  # "is the cup on the table?"
    if head == ("how",):
        social = starts(w, ("how", "are", "you")) or starts(w, ("how", "is", "it", "going"))
        return _q("how_are_you" if social else "other", w)
    if head and head[0] in WH:
        return _q("other", w)
    return None


def _what(w: Words) -> Parse:
    rest = w[1:]
    if "front" in rest or "around" in rest:
        return _q("what_see", w)
    if rest[:1] and rest[0] in _COLOUR_WORDS:
        return _q(
            "colour", w, thing=_strip_ends(rest[1:], frozenset({"is", "are"}), frozenset({"is", "are"}))
        )
    for sep in _LOCATIVES:
        found = split_at(("x", *rest), [sep])
        if found and not set(found[0][1:]) - _ON_GLUE:
            return _q("what_on", w, place=found[2])
    for i, word in enumerate(rest):  # "which cups do you see", "what fruit can you see"
        seeing = word in {"do", "can", "could"} and rest[i + 1 : i + 3] == ("you", "see")
        if seeing and i > 0 and not set(rest[:i]) & {"is", "are", "else"}:
            return _q("which_see", w, thing=rest[:i])
    if set(rest) & _SEE_WORDS and "name" not in rest:
        return _q("what_see", w)
    if rest[:1] in {("is",), ("are",)} and set(rest) & {"name", "called"}:
        return _q("name", w)
    if (
        rest[:1] in {("is",), ("are",)}
        and len(rest) > 1
        and not set(rest) & {"you", "your", "time", "weather"}
    ):
        return _q("what_is", w, thing=rest[1:])
    return _q("other", w)


def _where(w: Words) -> Parse:
    rest = w[1:]
    if rest in {("am", "i"), ("are", "we")}:
        return _q("where", w, thing=("me",))
    if rest == ("are", "you"):
        return _q("where", w, thing=("you",))
    for lead in _WHERE_LEADS:
        if starts(rest, lead):
            thing = _strip_ends(
                rest[len(lead) :], frozenset(), frozenset({"located", "now", "placed", "kept"})
            )
            if thing:
                return _q("where", w, thing=thing)
    return _q("other", w)
