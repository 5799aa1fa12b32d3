"""An utterance's words as the grammar reads them: plain words (dialogue.understanding.speech.plain) with the
self-repairs applied and a leading vocative dropped, and verbs as lemmas. These need the verbs of
the frame table ("bring me the uh no wait *put* the candle...", "john *can you* go...").
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

from lemminflect import getInflection

from dialogue.reference.english import Words
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.requests.frames import known_verbs, verbs
from dialogue.understanding.said import Said, Text
from dialogue.understanding.speech.plain import (
    expanded,
    my_for_me,
    plain,
    starts,
    strip_politeness,
    unrepeated,
    without_fillers,
)


class _Repairs:
    """A language's self-repairs and vocatives, as the functions below read them (made once per
    language)."""

    def __init__(self, lang: Language) -> None:
        speech = lang.speech
        self.repairs = speech.repairs
        self.markers = frozenset(speech.repairs)
        self.cancels = speech.cancels
        self.marker_starts = frozenset(m[0] for m in speech.repairs)
        #: The markers a word may start, in the order they are tried ("no" alone last).
        self.markers_at: dict[str, tuple[Words, ...]] = {}
        for marker in (*speech.repairs, *speech.repairs_alone):
            self.markers_at[marker[0]] = (*self.markers_at.get(marker[0], ()), marker)
        #: Prepositions that start a place said again ("...on the trolley no on the desk").
        self.place_words = frozenset(w for p in lang.prepositions.having("place") for w in p[:1])
        self.np_start = lang.words.np_start
        #: "one", "ones": said for the head of a phrase said before ("no, the blue one").
        self.one = lang.words.one
        self.modifier_start = lang.modifier_start
        self.fillers = speech.fillers
        self.lead_fillers = speech.lead_fillers
        self.not_vocative = speech.not_vocative
        self.polite_prefixes = speech.polite_prefixes


@lru_cache(maxsize=4096)
def verb_lemma(lang: Language, word: str) -> str:
    """The table's verb a word is an inflection of ("picking" -> "pick", "took" -> "take", "puts"
    -> "put"), else the word unchanged. Auxiliaries stay ("does you..." is not "do")."""
    known = known_verbs(lang)
    if word in known or word in lang.speech.auxiliaries:
        return word
    lemmas: tuple[str, ...] = lemmas_of(word).get("VERB", ())
    return next((lemma for lemma in lemmas if lemma in known), word)


@lru_cache(maxsize=4096)
def asked_verb(lang: Language, word: str) -> str | None:
    """The table's verb when the word is one as a request says it: the bare verb, or its -ing form
    after "would you mind" ("picking"); None otherwise. "Someone *left* the keys" is no request,
    so a past or third-person form never makes the word before it a vocative."""
    lemma = verb_lemma(lang, word)
    if lemma not in known_verbs(lang):
        return None
    return lemma if word == lemma or word in getInflection(lemma, "VBG") else None


def normalise(lang: Language, text: Text) -> list[str]:
    """Lower-case words with contractions expanded, fillers and stutters removed and a self-repair
    applied ("put the put the knife uh on the table", "bring me the uh no wait put the candle...")."""
    return list(Said.read(lang, text).form(_normalised))


def _normalised(u: Said) -> tuple[str, ...]:
    return tuple(repaired(u.lang, plain(u.lang, u)))


#: A word cut off with a dash and said again in full ("the box of para- paracetamol", "the ca— the
#: capo" is a repeat of its own): the part before the dash starts the next word.
_CUT_OFF = re.compile(r"\b(\w+)[-\u2013\u2014]\s+(?=\1\w)", re.IGNORECASE)


def restarted(text: str) -> str:
    """The text without the words cut off and said again in full ("para- paracetamol")."""
    return _CUT_OFF.sub("", text)


@dataclass(frozen=True)
class Cleaned:
    """An utterance with its stutters and self-repair resolved."""

    text: str
    #: What a self-repair took back ("hand Ravi the uh no wait..."): no request any more, but what
    #: its pronouns may refer to ("...bring her the muffin").
    taken_back: str = ""


def cleaned(lang: Language, text: Text) -> Cleaned:
    """The text with stutters and self-repairs resolved, when it has any (else unchanged, so that
    quoted words and casing survive): what a compound request is cut in."""
    return Said.read(lang, text).form(_cleaned)


def _cleaned(u: Said) -> Cleaned:
    lang = u.lang
    words = without_fillers(lang, expanded(lang, u))
    before, fixed = repair(lang, unrepeated(my_for_me(lang, words)))
    if fixed == words:
        return Cleaned(u.text)
    return Cleaned(" ".join(fixed), " ".join(before) if before != fixed[: len(before)] else "")


def repaired(lang: Language, words: list[str]) -> list[str]:
    return repair(lang, words)[1]


def repair(lang: Language, words: list[str]) -> tuple[list[str], list[str]]:
    """The words a self-repair took back and what the utterance says with it applied: after the
    last repair marker, a new request replaces the one before it ("bring me the uh no wait put the
    candle..."), a noun phrase the last one ("pick up the black umbrella no the yellow one": the
    yellow umbrella)."""
    said = lang.derived(_Repairs)
    for i in range(len(words) - 1, 0, -1):
        for marker in said.markers_at.get(words[i], ()):
            if tuple(words[i : i + len(marker)]) != marker:
                continue
            after = words[i + len(marker) :]
            # "no wait" rather than its "wait" alone: the whole marker is taken back
            start = next((i - k for k in (2, 1) if tuple(words[i - k : i + len(marker)]) in said.markers), i)
            if after[:1] and after[0] in said.marker_starts:
                continue  # "no wait ...": the longer marker, read at its own place
            cancel = next((c for c in said.cancels if tuple(after[-len(c) :]) == c), None)
            if cancel is not None:  # "...no wait, it isn't yet. Never mind": nothing is asked any more
                return words[:start], list(cancel)
            request = strip_politeness(lang, after)
            if request and asked_verb(lang, request[0]) in verbs(lang):
                return words[:start], after
            again = _said_again(lang, request)
            if again:  # "give this banana to... no, the pear, give the pear to Diego"
                return words[:start], again
            if request and (request[0] in said.np_start or request[0] in said.place_words):
                fixed = _rephrased(said, words[:start], request)
                if fixed is not None:
                    return words[:start], fixed
    return words, words


def _said_again(lang: Language, phrase: list[str]) -> list[str]:
    """The request a repair's noun phrase is followed by ("no, the pear, give the pear to Diego": the
    request said again whole), else []."""
    if not phrase or phrase[0] not in lang.words.np_start:
        return []
    starts = lang.requests.compound.object_start
    return next((phrase[k:] for k in range(2, len(phrase) - 1)
                 if asked_verb(lang, phrase[k]) in verbs(lang) and phrase[k + 1] in starts), [])  # fmt: skip


def _rephrased(said: _Repairs, before: list[str], phrase: list[str]) -> list[str] | None:
    """The request said before a repair with its last noun phrase said again (its head for "one"),
    or its last place ("put it on the shelf no wait on the desk")."""
    if phrase[0] in said.place_words:
        at = max((j for j in range(1, len(before)) if before[j] in said.place_words), default=None)
        return None if at is None else [*before[:at], *phrase]
    np_start = said.np_start
    starts = [j for j in range(1, len(before)) if before[j] in np_start and before[j - 1] not in np_start]
    if not starts:
        return None
    # The phrase said again is the one of the same head ("put the grey suitcase on the rack... I mean
    # the blue suitcase": the suitcase, not the rack), else the last.
    for at in reversed(starts):
        end = next((j for j in range(at + 1, len(before)) if before[j] in said.place_words), len(before))
        if _head(said, before[at:end]) == phrase[-1] and phrase[-1] not in said.one:
            return [*before[:at], *phrase, *before[end:]]
    # (the last, with the place or person said after it: "give the banana to Diego no the pear")
    last = starts[-1]
    end = next((j for j in range(last + 1, len(before)) if before[j] in said.place_words), len(before))
    head = _head(said, before[last:end])
    if head is None or head in np_start:
        return None
    return [*before[:last], *(head if w in said.one else w for w in phrase), *before[end:]]


def _head(said: _Repairs, phrase: list[str]) -> str | None:
    """A noun phrase's head: its word before a modifier or at its end."""
    return next((w for w, nxt in zip(phrase, [*phrase[1:], ""], strict=True)
                 if nxt in said.modifier_start or not nxt), None)  # fmt: skip


def strip_vocative(lang: Language, words: list[str], robot_name: str = "") -> list[str]:
    """ "john can you go to the bathroom", "michael go to the kitchen": the addressee's name (one
    word before a request) is not part of the request."""
    said = lang.derived(_Repairs)
    commands = verbs(lang)
    while len(words) > 2 and words[0] in said.lead_fillers and asked_verb(lang, words[1]) in commands:
        words = words[1:]
    if len(words) < 3 or words[0] in said.not_vocative or words[0] in commands or not words[0].isalpha():
        return words
    polite = any(starts(words[1:], p) and p[-1:] == ("you",) for p in said.polite_prefixes)
    if polite or asked_verb(lang, words[1]) in commands:
        return strip_politeness(lang, words[1:], robot_name)
    return words
