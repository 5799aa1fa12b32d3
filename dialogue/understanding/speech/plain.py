"""Speech-recogniser and chat text as plain words: contractions without apostrophes, fillers,
stutters, politeness; and the way back from words to the original text (its casing, its quotes).

Nothing here knows a verb: self-repairs and vocatives, which need the grammar's verbs, are in
dialogue.understanding.speech.repair.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache

from dialogue.reference.english import Words, lowered
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.said import Said, Text
from dialogue.understanding.tables.prefixes import Prefixes


class _Speech:
    """A language's speech and chat forms, as the functions below read them (made once per language:
    `lang.derived(_Speech)`)."""

    def __init__(self, lang: Language) -> None:
        speech, closed = lang.speech, lang.words
        self.lang = lang
        self.written = speech.written
        self.chat = speech.chat
        self.np_start = closed.np_start
        self.fillers = speech.fillers
        self.filler_pairs = speech.filler_pairs
        self.filler_pairs_before_verb = speech.filler_pairs_before_verb
        self.searching = Prefixes(speech.searching)
        self.asking = speech.asking
        self.wh_or_asking = closed.wh | speech.asking
        self.numbering = speech.numbering
        self.number_words = frozenset(w for words in closed.spoken_numbers.values() for w in words)
        self.not_nouns = speech.not_nouns
        self.function_words = closed.any_function_word
        self.numbers = closed.numbers
        self.determiners = closed.determiners
        self.my_after = speech.my_after
        self.no_noun = closed.any_function_word | closed.np_start
        self.robot_suffixes = speech.robot_suffixes
        #: The politeness at the end, longest first ("right now" before its "now").
        self.suffixes = sorted(speech.all_polite_suffixes, key=len, reverse=True)
        #: The same by their last word, still longest first: a turn tries only those its last word
        #: can end (a few of some hundred).
        self.suffixes_by_last: dict[str, tuple[Words, ...]] = {}
        for suffix in self.suffixes:
            if suffix:
                self.suffixes_by_last[suffix[-1]] = (*self.suffixes_by_last.get(suffix[-1], ()), suffix)
        #: Prepositions that a politeness word at the end completes ("for now", "till then", "by
        #: now"), or whose object a word naming the listener is ("take it to sir": whom, not a tag).
        self.left_behind = lang.prepositions.words("completes")
        #: After "could we", "can we": words that ask for a thing to be brought ("could we get the
        #: bill", "can we have two coffees"), when a noun phrase follows them ("can we get over to
        #: the desk" goes).
        self.wishing = speech.wishing
        self.durations = Prefixes(lang.requests.durations)
        self.polite_prefixes = speech.polite_prefixes
        self.its, self.it_is = speech.its, speech.it_is
        self.participle_endings = speech.participle_endings
        self.is_it_is = lru_cache(maxsize=4096)(self._is_it_is)
        self.openings = lru_cache(maxsize=64)(self._openings)

    def _is_it_is(self, after: tuple[str, ...]) -> bool:
        """Whether "its" before these words is "it's" written without its apostrophe: before a
        function word ("its the tall one", "its on the shelf"), a participle ("its stopped raining")
        or a last adjective ("its empty"); a possessive has a noun after it."""
        if not after:
            return True
        nxt = after[0]
        if nxt in self.function_words or nxt in self.determiners or nxt in self.not_nouns:
            return True
        if len(after) == 1 and nxt.endswith("'s"):  # "its Carla's": whose it is
            return True
        lemmas = lemmas_of(nxt)
        if nxt.endswith(self.participle_endings) and "VERB" in lemmas and "NOUN" not in lemmas:
            return True
        return len(after) == 1 and "ADJ" in lemmas

    def _openings(self, robot_name: str) -> dict[str, tuple[Words, ...]]:
        """The polite openings (and the robot's name) by first word, the longest first: "would you
        be able to" before "would you"."""
        name = tuple(expanded(self.lang, robot_name)) if robot_name else ()
        by_first: dict[str, list[Words]] = {}
        for p in (*self.polite_prefixes, name):
            if p:
                by_first.setdefault(p[0], []).append(p)
        return {w: tuple(sorted(ps, key=len, reverse=True)) for w, ps in by_first.items()}

    def numbering_word(self, word: str, after: str) -> bool:
        """Whether the word only announces the number after it ("no" only before digits: "no one")."""
        return word in self.numbering and (after.isdigit() or (word != "no" and after in self.number_words))


def expanded(lang: Language, text: Text) -> list[str]:
    """The text's words with contractions expanded ("wheres" -> "where is"; "its" -> "it is" where
    no noun follows it: "its on the bench", "its empty", but "its lid")."""
    return list(Said.read(lang, text).form(_expanded))


def _expanded(u: Said) -> Words:
    said = u.lang.derived(_Speech)
    words = u.tokens
    out: list[str] = []
    for i, w in enumerate(words):
        if i > 0 and said.numbering_word(w, words[i + 1] if i + 1 < len(words) else ""):
            continue  # "screen number two", "room no 4": the number names it
        if w == said.its and said.is_it_is(tuple(words[i + 1 : i + 3])):
            out += said.it_is
        elif w in said.chat and i > 0 and (words[i - 1] in said.np_start or _capitalised(u, i)):
            # "the atm": the cash machine, not "at the moment"; "bring the pear to Fae": a name
            # written as one, not Scots "from"
            out.append(w)
        else:
            out += said.written.get(w, (w,))
    return tuple(out)


def _capitalised(u: Said, i: int) -> bool:
    """Whether the `i`-th token was written with a capital (a recogniser writes none)."""
    start = u.spans[i][1]
    return u.text[start : start + 1].isupper()


def plain(lang: Language, text: Text) -> list[str]:
    """The text's words with contractions expanded and fillers and stutters removed."""
    return list(Said.read(lang, text).form(_plain))


def _plain(u: Said) -> Words:
    return tuple(unrepeated(without_fillers(u.lang, expanded(u.lang, u))))


def without_fillers(lang: Language, words: list[str]) -> list[str]:
    """ "put the uh candle", "pick up the uh you know the cup": fillers wherever they are, "you know"
    mid-sentence but not in "do you know where...", a word searched for after the first word."""
    said = lang.derived(_Speech)
    words = [w for w in words if w not in said.fillers]
    drop: set[int] = set()
    for i in range(1, len(words)):  # "pick up the... what's it called... the tongs"
        found = said.searching.first(words, i)
        if found:
            drop.update(range(i, i + len(found)))
    for i in range(1, len(words) - 1):
        nxt = words[i + 2] if i + 2 < len(words) else ""
        two = tuple(words[i : i + 2])
        before_verb = two in said.filler_pairs_before_verb and bool(lemmas_of(nxt).get("VERB"))
        pair = two in said.filler_pairs or before_verb
        if pair and words[i - 1] not in said.asking and nxt not in said.wh_or_asking:
            drop.update((i, i + 1))
    return [w for i, w in enumerate(words) if i not in drop]


def my_for_me(lang: Language, words: list[str]) -> list[str]:
    """ "me" said for "my" before a noun, where "me" could be no object: after a particle or another
    "me" (British and Irish speech: "pick up me zimmer frame", "fetch me me cardigan")."""
    said = lang.derived(_Speech)
    out = list(words)
    for i in range(1, len(out) - 1):
        if out[i] == "me" and out[i - 1] in said.my_after and out[i + 1] not in said.no_noun:
            out[i] = "my"
    return out


def unrepeated(words: list[str]) -> list[str]:
    """ "put the put the knife", "the the jumper": an immediately repeated run of 1-3 words once."""
    out: list[str] = []
    for w in words:
        out.append(w)
        size = len(out)
        for n in (1, 2, 3):
            if size >= 2 * n and out[-n:] == out[-2 * n : -n] and not out[-1].isdigit():
                del out[-n:]
                break
    return out


def original_text(lang: Language, said: Text, words: Sequence[str]) -> str:
    """The part of the original text that the (normalised) words came from, with its casing."""
    heard = Said.read(lang, said)
    text = heard.text
    if len(lowered(text)) != len(text) or not words:
        return " ".join(words)
    written = lang.speech.written
    found = [(w, start, end) for word, start, end in heard.spans for w in written.get(word, (word,))]
    n = len(words)
    for i in range(len(found) - n + 1):
        if all(found[i + k][0] == words[k] for k in range(n)):
            return text[found[i][1] : found[i + n - 1][2]]
    return " ".join(words)


def message(lang: Language, spoken: Text, words: Sequence[str]) -> str:
    """What to say, as said: the original text from `words` to the end of the utterance, less the
    politeness addressed to the robot ("tell Ana her taxi is here now please": "her taxi is here
    now"; `words` were read without the "now", which is the message's)."""
    heard = Said.read(lang, spoken)
    text = heard.text
    if len(lowered(text)) != len(text) or not words:
        return original_text(lang, heard, words)
    said = lang.derived(_Speech)
    found = [(w, start, end) for word, start, end in heard.spans for w in said.written.get(word, (word,))]
    n = len(words)
    at = next((i for i in range(len(found) - n + 1) if [f[0] for f in found[i : i + n]] == list(words)), None)
    if at is None:
        return original_text(lang, heard, words)
    tail = found[at:]
    dropped = True
    while dropped and len(tail) > n:
        dropped = False
        if tail[-1][0] in said.fillers:
            tail, dropped = tail[:-1], True
            continue
        for suffix in said.robot_suffixes:
            if len(tail) - len(suffix) >= n and tuple(t[0] for t in tail[-len(suffix) :]) == suffix:
                tail, dropped = tail[: -len(suffix)], True
                break
    return text[tail[0][1] : tail[-1][2]]


def starts(words: Sequence[str], prefix: Sequence[str]) -> bool:
    return len(prefix) <= len(words) and tuple(words[: len(prefix)]) == tuple(prefix)


def strip_politeness(lang: Language, words: list[str], robot_name: str = "") -> list[str]:
    said = lang.derived(_Speech)
    openings = said.openings(robot_name)
    changed = True
    while changed and words:
        changed = False
        for p in openings.get(words[0], ()):
            # "can you see" is a question, not a polite request: keep it; "could we get the bill"
            # is a wish (dialogue.understanding.requests.constructions.wanting), not "get the bill".
            if starts(words, p) and not _asking(said, p, words[len(p) :]):
                words = words[len(p) :]
                changed = True
                break
        for s in said.suffixes_by_last.get(words[-1], ()) if words else ():
            # ("wait in the hall for now": "for now" says how long, its "now" is no politeness)
            dangling = len(words) > len(s) and words[-len(s) - 1] in said.left_behind
            if len(words) > len(s) and tuple(words[-len(s) :]) == s and not dangling:
                words = words[: -len(s)]
                changed = True
                break
    return words


def _asking(said: _Speech, opening: Words, after: list[str]) -> bool:
    """Whether a polite opening is part of what is asked: "can you *see*...", "could we *get the*..."
    (a wish of the speaker's; "could we get the menu to Ana" is a request to bring it to her)."""
    if opening[-1] == "you":
        return after[:1] == ["see"]
    if opening[-1] != "we" or len(after) < 2 or after[0] not in said.wishing or _for_someone(said, after[2:]):
        return False
    return after[1] in said.numbers or after[1] not in said.function_words


def _for_someone(said: _Speech, words: list[str]) -> bool:
    """Whether the words name whom or where a thing is for ("to Ana", "for table 4"; "for now" not)."""
    for i, w in enumerate(words):
        lasting = bool(said.durations.of(words, i))
        if w == "to" or (w == "for" and not lasting):
            return True
    return False


def split_at(words: Sequence[str], separators: Sequence[Words]) -> tuple[Words, str, Words] | None:
    """First occurrence (after position 0) of any separator phrase: (before, separator, after)."""
    for i in range(1, len(words)):
        for sep in separators:
            if tuple(words[i : i + len(sep)]) == sep:
                return tuple(words[:i]), " ".join(sep), tuple(words[i + len(sep) :])
    return None
