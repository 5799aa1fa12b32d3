"""Keyboard and recogniser typos ("teh", "plase", "thremos"): a word that nothing accounts
for, corrected to the one word of the vocabulary it is a slip of.

The vocabulary is what the rules can understand: the grammar's own words (its word lists and verb
frames) and every word of every name the KB accounts for (the lexicon's vocabulary, so it follows
the KB). rapidfuzz finds the vocabulary words within one or two edits (optimal string alignment:
a swap of two letters is one edit); those are then priced as typing slips: a missed or doubled
letter or a neighbouring key costs 1, two letters swapped or a double letter typed once or a letter
typed twice 0.8, a key far away 1.5, and in a word of
four letters or fewer only a swap or a neighbouring key counts ("lego" is not a slip of "leg"). A
word is corrected
only when exactly one vocabulary word is the cheapest within 1 (2 for words of eight letters or
more); two at the same price are ambiguous and nothing is changed.

Never corrected: names (a capital not at the start of a sentence), words of the vocabulary, known
English words (lemminflect's lexicon: "lamp" is not
a slip of "lamb" even when only a lamb is known), numbers, words with an apostrophe, and quoted text
(said as it is). A correction to a name (a referent) is a guess about what is meant, which the
caller may leave to a model (dialogue.llm.hybrid); one to a grammar word is not.
"""

from __future__ import annotations

from dataclasses import dataclass

from jellyfish import metaphone
from lemminflect import getInflection
from rapidfuzz import process
from rapidfuzz.distance import OSA

from dialogue.reference.english import lowered, phrases
from dialogue.reference.lexicon import Lexicon, singular
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.requests.frames import frames
from dialogue.understanding.said import Said, Taken, Text
from dialogue.understanding.speech.heardnames import heard_name
from dialogue.understanding.speech.homophones import misheard
from dialogue.understanding.tables.base import words_in

_FAR_KEY = 1.5
#: Two letters typed in the wrong order, the commonest slip of fast typing ("teh"): a little cheaper
#: than a neighbouring key, so that "teh" is "the", not "ten".
_SWAP = 0.8
_DOUBLE = 0.8
_SHORT = 4
_LONG = 8
#: A metaphone key this short ("T" for "to") says too little of a word to match it by its sound.
SHORTEST_KEY = 2


class _Slips:
    """A language's words of typing and hearing slips (made once per language)."""

    def __init__(self, lang: Language) -> None:
        speech, closed = lang.speech, lang.words
        keyboard = speech.spelling
        #: Each key of the keyboard, by its row and how far along it is.
        self.keys = {k: (r, c + keyboard.offsets[r]) for r, row in enumerate(keyboard.keyboard)
                     for c, k in enumerate(row)}  # fmt: skip
        #: Words after which "were" at the start of an utterance can only be "where".
        self.asked = speech.spelling.asked
        self.slips = speech.preposition_slips
        #: Who a preposition may introduce without an article ("four me": for me; "2 him").
        self.people = closed.me | lang.requests.referents.person_objects
        #: Particles of the way after which a preposition says where ("show him through two surgery
        #: one").
        particles = lang.frames.group_words("motion") | lang.frames.group_words("carry")
        self.way = particles | lang.prepositions.words("path")
        self.np_start = closed.np_start
        self.numbers = closed.numbers
        self.pronouns = closed.pronouns


@dataclass(frozen=True)
class Spelled:
    text: str
    #: Each word corrected, and what it was taken for (a guess when a name of the KB).
    corrections: tuple[Taken, ...] = ()

    @property
    def guessed(self) -> bool:
        return any(c.guess for c in self.corrections)


def corrected(spoken: Text, lexicon: Lexicon) -> Spelled:
    """The text with each slip corrected (outside quotes), and the corrections made."""
    slips = lexicon.lang.derived(_Slips)
    u = Said.read(lexicon.lang, spoken)
    text = u.text
    quoted = u.quoted
    fixes: list[tuple[int, int, Taken]] = []
    words = u.spans
    said = [w for w, _, _ in words]
    for n, (word, start, end) in enumerate(words):
        if any(a <= start < b for a, b in quoted) or _named(text, start):
            continue
        if n == 0 and word == "were" and words[1:2] and words[1][0] in slips.asked:
            # "were is the globe": "where" as a recogniser writes it
            fixes.append((start, end, Taken(word, "where", False)))
            continue
        if 0 < n < len(words) - 1 and word in slips.slips:
            if _slipped_preposition(slips, said, n, lexicon):
                fixes.append((start, end, Taken(word, slips.slips[word], False)))
            continue
        heard = misheard(said, n, lexicon)  # "the pear of goggles", "write now", "wait their"
        if heard is not None:
            fixes.append((start, end, Taken(word, heard, False)))
            continue
        if not _suspect(word, lexicon):
            continue
        split = _run_together(lexicon.lang, word)  # "goto"
        if split is not None:
            fixes.append((start, end, Taken(word, split, False)))
            continue
        # a person's name in another spelling before a slip of a word ("steven" is Stephen, not "seven")
        someone = n == 0 or said[n - 1] not in slips.np_start  # ("the kat" is no Kate)
        meant = (heard_name(word, lexicon) if someone else None) or _meant(word, lexicon)
        if meant is not None:
            fixes.append((start, end, Taken(word, meant, meant not in grammar_words(lexicon.lang))))
    if not fixes:
        return Spelled(text)
    if len(lowered(text)) != len(text):  # offsets of the lowered text are not the original's
        return Spelled(" ".join(_fixed_words(u, fixes)), tuple(f[2] for f in fixes))
    out, last = [], 0
    for start, end, fix in fixes:
        out += [text[last:start], fix.taken_for.capitalize() if text[start].isupper() else fix.taken_for]
        last = end
    return Spelled("".join([*out, text[last:]]), tuple(f[2] for f in fixes))


def _slipped_preposition(slips: _Slips, words: list[str], n: int, lexicon: Lexicon) -> bool:
    """Whether the n-th word is a preposition heard or typed as another word ("walk too the gate",
    "milk form the jug", "take it 2 Carol", "get the ladle four me", "take the soup two table
    four"): before a noun phrase, a person (a name, "me", "him"), or a name of the KB said without
    its article after a noun phrase that has ended or a particle of the way ("through two surgery
    one"). A real number is never lost: a number before a
    plural ("two apples"), a number ending a name ("table two"), after a determiner ("the two")."""
    before, after = words[n - 1], words[n + 1]
    if before in slips.np_start or before.isdigit() or before in slips.numbers:
        return False
    if not _ended(words, n, lexicon):
        return False  # ("platform 4 my train's late": the number of a name)
    if after in slips.np_start or after in slips.people or _someone(lexicon, words, n + 1):
        return True
    if not lexicon.names_at(words, n + 1) or singular(after) != after:
        return False
    return before in slips.pronouns or before in slips.way or lexicon.knows(before)


def _ended(words: list[str], n: int, lexicon: Lexicon) -> bool:
    """Whether no name of the KB goes on into the n-th word ("table two", "screen 2")."""
    starts = range(max(0, n - 4), n)
    return not any(len(name.words) > n - j for j in starts for name in lexicon.names_at(words, j))


def _someone(lexicon: Lexicon, words: list[str], i: int) -> bool:
    """Whether the name of a person of the KB starts at the i-th word ("ola", "dr mensah")."""
    found = (lexicon.snapshot.get(n.entity) for n in lexicon.names_at(words, i))
    return any(e is not None and e.kind == "person" for e in found)


def _named(text: str, start: int) -> bool:
    """A capital not at the start of a sentence: a name, written as meant ("greet Tim", not Tom)."""
    before = text[:start].rstrip()
    return text[start : start + 1].isupper() and bool(before) and before[-1] not in ".!?\"“"


def _fixed_words(u: Said, fixes: list[tuple[int, int, Taken]]) -> list[str]:
    meant = {start: fix.taken_for for start, _, fix in fixes}
    return [meant.get(start, word) for word, start, _ in u.spans]


#: The shortest part of a word typed together with the next ("goto": "go" and "to").
_PART = 2


def _run_together(lang: Language, word: str) -> str | None:
    """Two words of the grammar typed as one ("goto", "infront", "bringme"), when only one cut makes
    two of them ("someones" is someone's, not "some ones")."""
    grammar = grammar_words(lang)
    if word.endswith("s") and (word[:-1] in grammar or lemmas_of(word[:-1])):
        return None
    cuts = [(word[:k], word[k:]) for k in range(_PART, len(word) - _PART + 1)]
    found = [f"{a} {b}" for a, b in cuts if a in grammar and b in grammar]
    return found[0] if len(found) == 1 else None


def _suspect(word: str, lexicon: Lexicon) -> bool:
    """Whether nothing accounts for the word: not the grammar's, not the KB's, not English."""
    if len(word) < 3 or not word.isalpha() or word in grammar_words(lexicon.lang) or lexicon.knows(word):
        return False
    return not lemmas_of(word)


def _meant(word: str, lexicon: Lexicon) -> str | None:
    """The one word the word is a slip of; a plural's slip ("tisues") is the plural of the word its
    singular is a slip of (the KB's names are indexed singular: "box of tissues" by "tissue"). A
    word heard for the one word of the KB's names that sounds the same ("guitar pics": picks) is
    that word before a slip of the keys to another name (but not to a word of the grammar)."""
    meant = _nearest(word, lexicon)
    heard = None if meant in grammar_words(lexicon.lang) else _sounding(word, lexicon)
    if heard is not None:  # ("plase" is a slip of "please", a word of the grammar, as before)
        return heard
    if len(word) <= _SHORT or not word.endswith("s") or (meant is not None and not lexicon.knows(meant)):
        return meant
    one = _nearest(word[:-1], lexicon)
    if one is None or one not in lexicon.vocabulary or meant not in {None, one}:
        return meant
    plurals = getInflection(one, "NNS")  # ("glases": glasses, not glass)
    return plurals[0] if plurals else meant


def _sounding(word: str, lexicon: Lexicon) -> str | None:
    """The one word of the KB's names a letter apart, and no shorter, that sounds as the word
    does (its singular, for a plural: the names are indexed singular), said in the word's number;
    else None."""
    one = singular(word)
    key = metaphone(one)
    if len(key) < SHORTEST_KEY:
        return None
    near = process.extract(one, list(lexicon.vocabulary), scorer=OSA.distance, score_cutoff=1, limit=None)
    # (a recogniser drops no letter of what it heard: "lego" is not heard for "leg")
    alike = {c for c, _, _ in near if c != one and len(c) >= len(one) and metaphone(c) == key}
    if len(alike) != 1:
        return None
    meant = alike.pop()
    plurals = getInflection(meant, "NNS") if one != word else ()
    return plurals[0] if plurals else meant


def _nearest(word: str, lexicon: Lexicon) -> str | None:
    limit = 2 if len(word) >= _LONG else 1
    choices = _choices(lexicon)
    near = process.extract(word, choices, scorer=OSA.distance, score_cutoff=limit, limit=None)
    priced = sorted((typing_cost(lexicon.lang, word, choice), choice) for choice, _, _ in near)
    if not priced or priced[0][0] > limit or (len(priced) > 1 and priced[1][0] == priced[0][0]):
        return None
    return priced[0][1]


def _choices(lexicon: Lexicon) -> list[str]:
    grammar = grammar_words(lexicon.lang)
    return [*grammar, *(w for w in lexicon.vocabulary if w not in grammar)]


def typing_cost(lang: Language, said: str, meant: str) -> float:
    """The price of `said` as a slip of `meant` (optimal string alignment, keyboard-weighted)."""
    keys = lang.derived(_Slips).keys
    short = len(meant) <= _SHORT
    gap = 2.0 if short else 1.0  # a short word with a letter missing or added is another word
    previous2: list[float] = []
    previous = [j * gap for j in range(len(meant) + 1)]
    for i, a in enumerate(said, 1):
        row = [i * gap]
        for j, b in enumerate(meant, 1):
            # a doubled letter typed once or a letter typed twice ("helo", "tabble") is the commonest
            # slip of all after a swap
            extra = _DOUBLE if not short and i > 1 and a == said[i - 2] else gap
            missed = _DOUBLE if not short and j > 1 and b == meant[j - 2] else gap
            cost = min(previous[j] + extra, row[j - 1] + missed, previous[j - 1] + _key_distance(keys, a, b))
            if i > 1 and j > 1 and a == meant[j - 2] and said[i - 2] == b:
                cost = min(cost, previous2[j - 2] + _SWAP)
            row.append(cost)
        previous2, previous = previous, row
    return previous[-1]


def _key_distance(keys: dict[str, tuple[int, float]], a: str, b: str) -> float:
    if a == b:
        return 0.0
    ka, kb = keys.get(a), keys.get(b)
    if ka is None or kb is None:
        return _FAR_KEY
    return 1.0 if abs(ka[0] - kb[0]) <= 1 and abs(ka[1] - kb[1]) <= 1 else _FAR_KEY


def grammar_words(lang: Language) -> frozenset[str]:
    """Every word the grammar itself uses: its word lists and the words of its verb frames (read
    once per language)."""
    return lang.derived(_grammar_words)


#: The uses of the preposition table whose prepositions are the grammar's words.
_GRAMMAR_PREPOSITIONS = (
    "support", "locative", "modifier", "place", "goal", "goal-particle", "path", "terse-place", "asked-on",
    "asked-near", "place-start",
)  # fmt: skip


def _grammar_tables(lang: Language) -> tuple[object, ...]:
    """The tables whose words are the grammar's own: not the words of content (homophones, needs,
    preposition slips), nor those only one reader keeps to itself (a clause's, a statement's)."""
    closed, speech, said, social = lang.words, lang.speech, lang.requests, lang.social
    asked = lang.questions.situation
    return (
        closed.determiners, closed.pronouns, closed.personal, closed.neuter, closed.possessives, closed.me,
        closed.colours, closed.positions, closed.parts, closed.containers, closed.compound_heads,
        closed.measures, closed.many, closed.relativisers, closed.titles, closed.any_function_word,
        closed.written, closed.np_start, closed.owners, closed.wh,
        *(lang.prepositions.having(use) for use in _GRAMMAR_PREPOSITIONS),
        lang.prepositions.column("reads_as"),
        speech.written, speech.fillers, speech.filler_pairs, speech.filler_pairs_before_verb, speech.asking,
        speech.repairs,
        speech.polite_prefixes, speech.all_polite_suffixes, speech.not_vocative, speech.lead_fillers,
        speech.auxiliaries,
        social.greetings, social.attention, social.social,
        said.here, said.there, said.all_adjuncts, said.while_, said.time_conjunctions, said.their_subjects,
        said.polite_if, said.if_modals, said.halts, said.manner, said.wants, said.want_verbs,
        said.their_wants, said.wishers, said.not_wishers, said.purposes, said.intensifiers, said.done,
        said.goes, said.goes_particles, said.terse_motion, said.everyone, said.stop_filler,
        said.activity_filler, said.results, said.no_intent_verbs,
        lang.followups.interjections,
        asked.sees, asked.where_leads, asked.on_glue, asked.who_not_a_name, asked.see_words,
        asked.colour_words, asked.indirect, asked.be, asked.someone, asked.else_, asked.owners, asked.nearby,
        asked.others, asked.there, asked.asking_verbs, asked.asked_subjects, asked.count_tail,
        *(lang.frames.groups.get(name, "") for name in ("motion", "carry")),
    )


def _grammar_words(lang: Language) -> frozenset[str]:
    found: set[str] = set()
    for table in _grammar_tables(lang):
        found.update(words_in(table))
    for frame in frames(lang):
        texts = (frame.verbs, frame.particles, *frame.slots.values())
        found.update(w for text in texts for p in phrases(text) for w in p)
    return frozenset(w for w in found if w.isalpha())

