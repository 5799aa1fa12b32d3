"""An utterance cut into its clauses, and the clauses that only describe what a request names.

Written speech has punctuation; a speech recogniser's has none, so a request and the remark that
follows it run on: "hand me the torch i can't see the clock", "drive Omar to the gate the
bus leaves soon". A clause starts at a punctuation mark or dash, at a polite request said
mid-utterance ("it's cold can I have a blanket"), and where a subject and its verb start again: a
subject pronoun before a verb ("she's doing sprints"), or a name or a noun phrase before a verb that
agrees with it ("Omar wants a word", "the bus leaves soon").

A clause after a request may describe the thing it asks for: "fetch my bag, it's the blue one
by the door", "get my keys, I think they're in the hall", "the cup I left on the table". Its
words qualify the request's object (`described`).

Words only: which clause is a request, and what its phrases name, is decided by the interpreter.
"""

from __future__ import annotations

import re
from functools import lru_cache
from itertools import pairwise

from lemminflect import getAllLemmas, getInflection

from dialogue.reference.english import (
    DETERMINERS,
    FUNCTION_WORDS,
    MODIFIER_START,
    Words,
    lowered,
    phrases,
    spans,
    word_set,
)
from dialogue.understanding.language import Language
from dialogue.understanding.speech.plain import expanded, strip_politeness
from dialogue.understanding.words import NP_START, OWNERS, TAGS

#: Punctuation and dashes end a clause.
_BREAK = re.compile(r"[.;!?,]+(?:\s+|$)|\s+(?:-|\u2013|\u2014)\s+")
#: A polite request said mid-utterance starts a clause of its own.
_ASKS = phrases("could you|can you|would you|will you|please|can i have|could i have|may i have|can i get|"
                "could i get|do you know where|do you know who|do you know if|do you know whether|"
                "do you know what|any idea where|any idea who")
#: Subjects that are no one in particular ("pick up the umbrella *someone left* it here").
_INDEFINITE = word_set("someone somebody everyone everybody nobody anyone anybody")
_SUBJECTS = word_set("i he she it we they you there") | _INDEFINITE
#: Verbs that follow any subject: auxiliaries, modals and their negations.
_AUXILIARIES = word_set(
    "am is are was were has have had will would can cannot could should might must shall may do does did "
    "don't didn't doesn't won't wouldn't couldn't shouldn't isn't aren't wasn't just really also"
)
#: Words after which a subject pronoun is an object or a clause the verb takes ("tell him she is...").
_TAKES_CLAUSE = word_set(
    "that if whether when because so tell ask let make have help and or but think believe guess reckon "
    "suppose know hope say said where who what which how why"
)
#: Verbs whose object comes before the clause they take ("tell him she's here").
_TELLING = word_set("tell told ask remind warn inform show promise let")
#: Conjunctions that start a clause of reason after a request ("... because she has to take them").
_REASONS = word_set("because cos cause since as so")
#: Words that soften a request said after a remark ("you're blocking the door *maybe* go...").
_HEDGES = word_set("maybe perhaps just now then so")
#: Words naming the listener at the end of a remark ("you're in the way *mate* go...").
_TAGS = frozenset(w for p in phrases(TAGS) for w in p[-1:])
#: Words a described thing is said with: "it's the tall one", "I think they're in the drawer".
_DESCRIBING = (("it", "is"), ("they", "are"), ("it", "was"), ("they", "were"), ("it", "should", "be"))
_THINKING = (("i", "think"), ("i", "believe"), ("i", "guess"), ("probably",), ("maybe",), ("i", "reckon"))
#: "the cup I left on the table": a clause of the speaker's that says where the thing was put.
_PUT = word_set("left put placed dropped saw had")


def clauses(lang: Language, text: str) -> list[str]:
    """The text's clauses, as parts of the original text (its casing kept), in order."""
    out: list[str] = []
    for piece in _BREAK.split(text):
        if piece.strip():
            out.extend(_run_on(lang, piece.strip()))
    return out


def _run_on(lang: Language, text: str) -> list[str]:
    """A clause without punctuation cut where a new clause starts."""
    if len(lowered(text)) != len(text):
        return [text]
    toks = spans(text)
    words = [expanded(lang, w) for w, _, _ in toks]
    cuts = [i for i in range(1, len(toks)) if _starts_clause(words, i)]
    if not cuts:
        return [text]
    bounds = [0, *cuts, len(toks)]
    return [text[toks[a][1] : toks[b - 1][2]] for a, b in pairwise(bounds) if b > a]


def _starts_clause(words: list[list[str]], i: int) -> bool:
    """Whether the i-th word (each word with its contraction expanded) starts a clause."""
    flat = [w for ws in words[i:] for w in ws]
    before = words[i - 1][-1]
    asked = next((a for a in _ASKS if tuple(flat[: len(a)]) == a), None)
    if asked is not None:
        after = flat[len(asked) : len(asked) + 1]
        if asked[-1] == "you" and (not after or after[0] in _SUBJECTS - {"you"}):
            return False  # a tag: "pick up my frame would you (it's fallen over)"
        return before not in {"you", "i", "that", "if", "and", "or"}
    told = i > 1 and words[i - 2][-1] in _TELLING
    if before in _TAKES_CLAUSE or before in _AUXILIARIES or told or len(flat) < 2:
        return False  # "I think it's...", "tell him she's here"; "can I have": a question's order
    first, second = flat[0], flat[1]
    if first in _HEDGES and before not in _SUBJECTS and _bare_verb(second):
        return True  # "move out of the way a bit *maybe go* over to the counter"
    tagged = i > 1 and before in _TAGS and words[i - 2][-1] not in _SUBJECTS | NP_START
    if tagged and _bare_verb(first):
        return True  # "you're in the way mate *go* over by the door"
    if first in _REASONS:  # "... because she has to take them before dinner"
        return len(flat) > 2 and second in _SUBJECTS and _subject_verb(second, flat[2])
    if first in _SUBJECTS:
        return _subject_verb(first, second)
    if before in NP_START or before in MODIFIER_START or first in FUNCTION_WORDS - NP_START - {"her"}:
        return False
    if first in NP_START or first == "her":  # "the bus leaves soon": a phrase of one or two words, its verb
        return any(_agrees(flat, k) for k in (2, 3) if not set(flat[1:k]) & (FUNCTION_WORDS | DETERMINERS))
    # "Omar wants a word": a word that is a name or a noun, then its verb
    name = first.isalpha() and first not in _AUXILIARIES and not set(getAllLemmas(first)) - {"NOUN", "PROPN"}
    return name and _agrees(flat, 1)


@lru_cache(maxsize=4096)
def _bare_verb(word: str) -> bool:
    """Whether the word is a verb as a request starts with it ("go", "put"), not in a tense."""
    return word in getAllLemmas(word).get("VERB", ()) and word not in FUNCTION_WORDS


def _subject_verb(subject: str, verb: str) -> bool:
    """Whether a subject pronoun and the word after it start a clause ("she is", "I can't")."""
    if subject == "you":
        return verb in _AUXILIARIES and verb not in {"do", "does", "did", "just", "really", "also"}
    return verb in _AUXILIARIES or finite(verb, third_person=subject in {"he", "she", "it"} | _INDEFINITE)


def _agrees(flat: list[str], k: int) -> bool:
    """Whether the word at k is a verb agreeing with the noun phrase before it."""
    if k >= len(flat):
        return False
    verb, after = flat[k], flat[k + 1] if k + 1 < len(flat) else ""
    if after == "you" and verb in _AUXILIARIES:
        return False  # "(pick up) my frame would you": a tag question's order, no subject before it
    if verb in {"is", "was", "has"}:
        return True
    lemmas = getAllLemmas(verb)
    if not finite(verb, third_person=True):
        return False
    # "the class starts soon", "the baby needs a nap"; but "the reading glasses (on the table)" is
    # a plural noun: one that may be either is a verb only before an adverb or an object
    adverb = after not in FUNCTION_WORDS and set(getAllLemmas(after)) == {"ADV"}
    return "NOUN" not in lemmas or after in NP_START or adverb


@lru_cache(maxsize=4096)
def finite(word: str, third_person: bool) -> bool:
    """Whether the word is a verb in a tense ("wants", "started"; "want" too after "I", "we"...)."""
    for lemma in getAllLemmas(word).get("VERB", ()):
        forms = {*getInflection(lemma, "VBZ"), *getInflection(lemma, "VBD")} if third_person else set()
        forms |= set() if third_person else {lemma, *getInflection(lemma, "VBD")}
        if word in forms:
            return True
    return False


def description(lang: Language, text: str) -> Words | None:
    """What a clause that describes the thing just asked for says of it ("it's the blue one by the
    door": the blue one by the door; "I think they're in the hall": in the hall; "I left it
    on the bench": on the bench), or None when the clause is not one."""
    words = strip_politeness(lang, expanded(lang, text))
    for lead in _THINKING:
        if tuple(words[: len(lead)]) == lead:
            words = words[len(lead) :]
    said = next((len(d) for d in _DESCRIBING if tuple(words[: len(d)]) == d), None)
    if said is None and words[:1] == ["i"] and words[1:2] and words[1] in _PUT:
        said = 3 if words[2:3] in (["it"], ["them"]) else 2
    if said is None:
        return None
    rest = tuple(words[said:])
    located = rest[:1] and rest[0] in MODIFIER_START and len(rest) > 1
    one = rest[:1] and rest[0] in NP_START and ("one" in rest or "ones" in rest)
    whose = len(rest) == 1 and (rest[0].endswith("'s") or rest[0] in OWNERS)  # "it's Carla's"
    return rest if located or one or whose else None


def described(lang: Language, thing: Words, said: Words) -> Words:
    """The request's phrase for a thing with what a later clause said of it: "my bag" and "the
    blue one by the door" make "my blue bag by the door"."""
    if said[0] in MODIFIER_START:
        return (*thing, *said)
    if len(said) == 1:  # whose it is: "the pink phone" and "Carla's" make "Carla's pink phone"
        return (OWNERS.get(said[0], said[0]), *(w for w in thing if w not in NP_START))
    lead = tuple(w for w in thing if w in NP_START)
    head = tuple(w for w in thing if w not in NP_START)
    return (*lead, *(x for w in said[1:] for x in (head if w in {"one", "ones"} else (w,))))
