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

from lemminflect import getInflection

from dialogue.reference.english import Words, lowered
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.said import Said, Text
from dialogue.understanding.speech.plain import expanded, strip_politeness

#: Punctuation and dashes end a clause ("one more thing: lead Marcus to the study").
_BREAK = re.compile(r"[.;:!?,]+(?:\s+|$)|\s+(?:-|\u2013|\u2014)\s+")


class _Clauses:
    """A language's words of clauses (`speech.toml` [clauses]), as the functions below read them
    (made once per language)."""

    def __init__(self, lang: Language) -> None:
        said, closed = lang.speech.clauses, lang.words
        #: A polite request said mid-utterance starts a clause of its own.
        self.asks = said.asks
        #: The same by their first word, in their order.
        self.asks_at: dict[str, tuple[Words, ...]] = {}
        for ask in self.asks:
            self.asks_at[ask[0]] = (*self.asks_at.get(ask[0], ()), ask)
        #: Subjects that are no one in particular ("pick up the umbrella *someone left* it here").
        self.indefinite = said.indefinite
        self.subjects = said.subjects | said.indefinite
        #: Verbs that follow any subject: auxiliaries, modals and their negations.
        self.auxiliaries = said.auxiliaries
        #: Words after which a subject pronoun is an object or a clause the verb takes.
        self.takes_clause = said.takes_clause
        #: Verbs whose object comes before the clause they take ("tell him she's here").
        self.telling = said.telling
        self.reasons = said.reasons
        self.hedges = said.hedges
        #: Words naming the listener at the end of a remark ("you're in the way *mate* go...").
        self.tags = frozenset(w for p in lang.speech.tags for w in p[-1:])
        self.describing = said.describing
        self.thinking = said.thinking
        self.put = said.put
        self.np_start = closed.np_start
        self.modifier_start = lang.modifier_start
        self.function_words = closed.any_function_word
        self.determiners = closed.determiners
        self.owners = closed.owners
        self.not_before_ask = said.not_before_ask
        self.not_after_you = said.not_after_you
        self.third_person = said.third_person | said.indefinite
        self.agreeing = said.agreeing
        self.one = closed.one
        # The sets `_starts_clause` reads, made once here rather than on each of a turn's words.
        self.subjects_but_you = self.subjects - {"you"}
        self.subjects_or_np_start = self.subjects | self.np_start
        self.no_subject_start = self.function_words - self.np_start - {"her"}
        self.closed_in_phrase = self.function_words | self.determiners


def clauses(lang: Language, text: Text) -> list[str]:
    """The text's clauses, as parts of the original text (its casing kept), in order."""
    return list(Said.read(lang, text).form(_clauses))


def _clauses(u: Said) -> tuple[str, ...]:
    out: list[str] = []
    for piece in _BREAK.split(u.text):
        if piece.strip():
            out.extend(_run_on(u.of(piece.strip())))
    return tuple(out)


def _run_on(u: Said) -> list[str]:
    """A clause without punctuation cut where a new clause starts."""
    lang, text = u.lang, u.text
    if len(lowered(text)) != len(text):
        return [text]
    said = lang.derived(_Clauses)
    toks = u.spans
    words = [expanded(lang, u.word(w)) for w, _, _ in toks]
    # Where each word's expansion starts in the words all expanded: each candidate reads the rest.
    flat = [w for ws in words for w in ws]
    starts = [0]
    for ws in words:
        starts.append(starts[-1] + len(ws))
    cuts = [i for i in range(1, len(toks)) if _starts_clause(said, words, i, flat[starts[i] :])]
    if not cuts:
        return [text]
    bounds = [0, *cuts, len(toks)]
    return [text[toks[a][1] : toks[b - 1][2]] for a, b in pairwise(bounds) if b > a]


def _starts_clause(said: _Clauses, words: list[list[str]], i: int, flat: list[str]) -> bool:
    """Whether the i-th word (each word with its contraction expanded; `flat`: the words from it on,
    expanded) starts a clause."""
    before = words[i - 1][-1]
    asks = said.asks_at.get(flat[0], ()) if flat else ()
    asked = next((a for a in asks if tuple(flat[: len(a)]) == a), None)
    if asked is not None:
        after = flat[len(asked) : len(asked) + 1]
        if asked[-1] == "you" and (not after or after[0] in said.subjects_but_you):
            return False  # a tag: "pick up my frame would you (it's fallen over)"
        return before not in said.not_before_ask
    told = i > 1 and words[i - 2][-1] in said.telling
    if before in said.takes_clause or before in said.auxiliaries or told or len(flat) < 2:
        return False  # "I think it's...", "tell him she's here"; "can I have": a question's order
    first, second = flat[0], flat[1]
    if first in said.hedges and before not in said.subjects and _bare_verb(said, second):
        return True  # "move out of the way a bit *maybe go* over to the counter"
    tagged = i > 1 and before in said.tags and words[i - 2][-1] not in said.subjects_or_np_start
    if tagged and _bare_verb(said, first):
        return True  # "you're in the way mate *go* over by the door"
    if first in said.reasons:  # "... because she has to take them before dinner"
        return len(flat) > 2 and second in said.subjects and _subject_verb(said, second, flat[2])
    if first in said.subjects:
        return _subject_verb(said, first, second)
    np_start = said.np_start
    if before in np_start or before in said.modifier_start or first in said.no_subject_start:
        return False
    if first in np_start or first == "her":  # "the bus leaves soon": a phrase of one or two words, its verb
        closed = said.closed_in_phrase
        return any(_agrees(said, flat, k) for k in (2, 3) if not set(flat[1:k]) & closed)
    # "Omar wants a word": a word that is a name or a noun, then its verb
    noun = not set(lemmas_of(first)) - {"NOUN", "PROPN"}
    return first.isalpha() and first not in said.auxiliaries and noun and _agrees(said, flat, 1)


def _bare_verb(said: _Clauses, word: str) -> bool:
    """Whether the word is a verb as a request starts with it ("go", "put"), not in a tense."""
    return _verb_lemma_itself(word) and word not in said.function_words


@lru_cache(maxsize=4096)
def _verb_lemma_itself(word: str) -> bool:
    """Whether the word is a verb's lemma ("go", "put"; not "went")."""
    return word in lemmas_of(word).get("VERB", ())


def _subject_verb(said: _Clauses, subject: str, verb: str) -> bool:
    """Whether a subject pronoun and the word after it start a clause ("she is", "I can't")."""
    if subject == "you":
        return verb in said.auxiliaries and verb not in said.not_after_you
    third = subject in said.third_person
    return verb in said.auxiliaries or finite(verb, third_person=third)


def _agrees(said: _Clauses, flat: list[str], k: int) -> bool:
    """Whether the word at k is a verb agreeing with the noun phrase before it."""
    if k >= len(flat):
        return False
    verb, after = flat[k], flat[k + 1] if k + 1 < len(flat) else ""
    if after == "you" and verb in said.auxiliaries:
        return False  # "(pick up) my frame would you": a tag question's order, no subject before it
    if verb in said.agreeing:
        return True
    lemmas = lemmas_of(verb)
    if not finite(verb, third_person=True):
        return False
    # "the class starts soon", "the baby needs a nap"; but "the reading glasses (on the table)" is
    # a plural noun: one that may be either is a verb only before an adverb or an object
    adverb = after not in said.function_words and set(lemmas_of(after)) == {"ADV"}
    return "NOUN" not in lemmas or after in said.np_start or adverb


@lru_cache(maxsize=4096)
def finite(word: str, third_person: bool) -> bool:
    """Whether the word is a verb in a tense ("wants", "started"; "want" too after "I", "we"...)."""
    for lemma in lemmas_of(word).get("VERB", ()):
        forms = {*getInflection(lemma, "VBZ"), *getInflection(lemma, "VBD")} if third_person else set()
        forms |= set() if third_person else {lemma, *getInflection(lemma, "VBD")}
        if word in forms:
            return True
    return False


def description(lang: Language, text: Text) -> Words | None:
    """What a clause that describes the thing just asked for says of it ("it's the blue one by the
    door": the blue one by the door; "I think they're in the hall": in the hall; "I left it
    on the bench": on the bench), or None when the clause is not one."""
    clause = lang.derived(_Clauses)
    words = strip_politeness(lang, expanded(lang, text))
    for lead in clause.thinking:
        if tuple(words[: len(lead)]) == lead:
            words = words[len(lead) :]
    said = next((len(d) for d in clause.describing if tuple(words[: len(d)]) == d), None)
    if said is None and words[:1] == ["i"] and words[1:2] and words[1] in clause.put:
        said = 3 if words[2:3] in (["it"], ["them"]) else 2
    if said is None:
        return None
    rest = tuple(words[said:])
    located = rest[:1] and rest[0] in clause.modifier_start and len(rest) > 1
    one = rest[:1] and rest[0] in clause.np_start and bool(set(rest) & clause.one)
    whose = len(rest) == 1 and (rest[0].endswith("'s") or rest[0] in clause.owners)  # "it's Carla's"
    return rest if located or one or whose else None


def described(lang: Language, thing: Words, said: Words) -> Words:
    """The request's phrase for a thing with what a later clause said of it: "my bag" and "the
    blue one by the door" make "my blue bag by the door"."""
    np_start = lang.words.np_start
    if said[0] in lang.modifier_start:
        return (*thing, *said)
    if len(said) == 1:  # whose it is: "the pink phone" and "Carla's" make "Carla's pink phone"
        return (lang.words.owners.get(said[0], said[0]), *(w for w in thing if w not in np_start))
    lead = tuple(w for w in thing if w in np_start)
    head = tuple(w for w in thing if w not in np_start)
    return (*lead, *(x for w in said[1:] for x in (head if w in lang.words.one else (w,))))
