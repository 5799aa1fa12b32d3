"""Compound requests: one utterance, several commands in order ("go to the kitchen and take the plate").

An utterance is cut at "and", "then", "after that" or a comma when what follows starts with a verb
of the grammar, and before an imperative verb that starts a new command without any conjunction
("go to the bathroom take the rag"). Words only: what each part means is decided by the interpreter.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from dialogue.reference.english import Words, tokens
from dialogue.reference.grounding import Snapshot
from dialogue.reference.resolution import content_words
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.requests.frames import known_verbs, verbs
from dialogue.understanding.said import QUOTED, Said, Text
from dialogue.understanding.speech.plain import strip_politeness
from dialogue.understanding.speech.repair import asked_verb, normalise, strip_vocative
from dialogue.understanding.tables.prefixes import Prefixes


class _Words:
    """The language's words of compound requests (`requests.toml` [compound]; made once per language)."""

    def __init__(self, lang: Language) -> None:
        said = lang.requests.compound
        self.conjunctions = said.conjunctions
        #: Verbs that start a new command even with no conjunction before them, when followed by
        #: one of `object_start` ("go to the bathroom take the rag"): never nouns in a command's
        #: phrases.
        self.bare_verbs = said.bare_verbs
        self.serial = said.serial
        #: A greeting asked for starts a request of its own, whatever came before it ("Agnes is
        #: here say hi").
        self.greeting = said.greeting
        self.object_start = said.object_start
        #: Words after which a verb continues the same command ("you take", "to take", "go get"),
        #: besides the verbs of the grammar.
        self.no_cut_after = said.no_cut_after
        self.a_bit = said.a_bit
        self.away = lang.requests.away
        self.chat = lang.speech.chat
        self.greetings = Prefixes(lang.social.greetings_longest_first)
        self.no_intent_verbs = lang.requests.no_intent_verbs
        self.results = lang.requests.results


def _greeting_at(c: _Words, toks: list[tuple[str, int, int]], i: int) -> bool:
    return i + 1 < len(toks) and (toks[i][0], toks[i + 1][0]) in c.greeting


@dataclass(frozen=True)
class Part:
    text: str
    #: The verb the part starts with (None for a preamble such as "thanks" or "hello").
    verb: str | None
    #: The part's verb is one the robot has no intent for ("find", "turn on"; `requests.toml`).
    no_intent: bool
    #: The part only says where not to be ("move out of the way and go to the door"): what the
    #: parts after it do.
    aside: bool = False


def _verb(lang: Language, text: Text, later: bool = False) -> str | None:
    """The verb a part starts with; of a later part, also one no frame knows, said before what it
    is done to ("... and *inspect* it", "... and *count* the chairs")."""
    c = lang.derived(_Words)
    words = strip_politeness(lang, normalise(lang, text))
    for greeting in c.greetings.of(words):  # "hey robot take the book"
        if len(words) > len(greeting):
            words = strip_politeness(lang, words[len(greeting) :])
            break
    words = strip_vocative(lang, words)
    if not words:
        return None
    known = asked_verb(lang, words[0])
    if known is not None or not later or len(words) < 2:
        return known
    verb = words[0] in lemmas_of(words[0]).get("VERB", ())  # a verb as said to do it, not "chairs"
    return words[0] if verb and words[1] in c.object_start else None


def conjuncts(lang: Language, said: Text) -> list[Part]:
    """The commands of a compound request in order, or [] when the text is one request."""
    heard = Said.read(lang, said)
    if QUOTED.search(heard.text):  # "say 'stop and wait' to Tom": the quote is one text
        return []
    c = lang.derived(_Words)
    # (a conjunction as chat writes it: "get my bag n bring it over")
    toks = [(_one_word(c, word), start, end) for word, start, end in heard.marked]
    cuts = _cuts(lang, c, toks)
    if not cuts:
        return []
    parts, gapped = _joined_parts(lang, heard, toks, _ranges(cuts, len(toks)))
    if len(parts) < 2:
        return []
    out: list[Part] = []
    for n, (s, e) in enumerate(parts):
        piece = heard.text[toks[s][1] : toks[e - 1][2]].strip(" ,;")
        if n in gapped and out[-1].verb is not None:  # "... and then the bun to Mrs Kaur": bring it
            piece = f"{out[-1].verb} {piece}"
        out.append(_part(lang, c, heard.of(piece), piece, later=n > 0))
    return out


#: A token as `Said.marked` gives it: (word, start, end) in the text.
_Token = tuple[str, int, int]


def _cuts(lang: Language, c: _Words, toks: list[_Token]) -> list[tuple[int, int]]:
    """Where the text is cut: (index of the first word of the new part, index after the cut)."""
    no_cut_after = c.no_cut_after | verbs(lang) | c.conjunctions
    cuts: list[tuple[int, int]] = []
    for i, (word, _, _) in enumerate(toks):
        if i == 0:
            continue
        if word in c.conjunctions:
            j = i
            while j < len(toks) and toks[j][0] in c.conjunctions:
                j += 1
            if j < len(toks) and (not cuts or cuts[-1][1] <= i):
                cuts.append((i, j))
        elif _greeting_at(c, toks, i) and toks[i - 1][0] not in no_cut_after:
            cuts.append((i, i))  # "Agnes is here say hi"
        elif word in c.bare_verbs and toks[i - 1][0] not in no_cut_after and _bare_verb_at(lang, c, toks, i):
            cuts.append((i, i))
    return cuts


def _bare_verb_at(lang: Language, c: _Words, toks: list[_Token], i: int) -> bool:
    """Whether the bare verb at i starts a request: before what it is done to, or before a verb."""
    word = toks[i][0]
    nxt = toks[i + 1][0] if i + 1 < len(toks) else ""
    # "...he is at the door go say hi to him": "go" or "come" before a verb starts a request too
    serial = word in c.serial and asked_verb(lang, nxt) in verbs(lang)
    said_after = content_words(lang, [w for w, _, _ in toks[i + 1 :]])  # ("where did it get to")
    return bool(nxt in c.object_start and said_after) or serial


def _ranges(cuts: list[tuple[int, int]], size: int) -> list[tuple[int, int]]:
    """The token ranges of the parts the cuts leave."""
    ranges: list[tuple[int, int]] = []
    start = 0
    for end, resume in cuts:
        ranges.append((start, end))
        start = resume
    ranges.append((start, size))
    return ranges


def _joined_parts(
    lang: Language, heard: Said, toks: list[_Token], ranges: list[tuple[int, int]]
) -> tuple[list[tuple[int, int]], set[int]]:
    """The parts, a part with no verb of its own joined to the one before it ("the cereals and the
    milk": one), unless it says that part's verb again for another thing (gapped: the parts'
    numbers)."""
    text = heard.text
    parts: list[tuple[int, int]] = []
    gapped: set[int] = set()  # parts that say again the verb of the part before them
    for s, e in ranges:
        if s >= e:
            continue
        piece = text[toks[s][1] : toks[e - 1][2]]
        if parts and _verb(lang, heard.of(piece), later=True) is None:
            b, f = parts[-1]
            before = [w for w, _, _ in toks[b:f]]
            said_before = _verb(lang, heard.of(text[toks[b][1] : toks[f - 1][2]]))
            if said_before is not None and _gaps(lang, before, [w for w, _, _ in toks[s:e]]):
                gapped.add(len(parts))
                parts.append((s, e))
            else:  # "the cereals and the milk": one
                parts[-1] = (parts[-1][0], e)
        else:
            parts.append((s, e))
    return parts, gapped


def _part(lang: Language, c: _Words, said: Said, piece: str, later: bool) -> Part:
    verb = _verb(lang, said, later=later)
    # ("go to the x-ray room and get it ready": no intent says the getting ready)
    words = normalise(lang, said)
    result = verb is not None and bool(words) and words[-1] in c.results
    unknown = verb is not None and verb not in known_verbs(lang)  # "... and count the chairs"
    no_intent = verb in c.no_intent_verbs or result or unknown
    return Part(piece, verb, no_intent, _away(lang, said))


def _gaps(lang: Language, before: list[str], words: list[str]) -> bool:
    """Whether a part with no verb says the request before it again for another thing: "bring the
    lemonade to Ruby and then the bun to Mrs Kaur", "put the cup on the shelf and the plate on the
    table" (a thing, then the preposition of the same role the part before said, then whom or where;
    the caller knows the part before starts with a verb); "bring the cereals and the milk to the
    table" is one request of two things."""
    roles = lang.prepositions.words("terse-to") | lang.prepositions.words("terse-place")
    at = next((i for i, w in enumerate(words) if w in roles), None)
    if at is None or not content_words(lang, words[:at]) or not content_words(lang, words[at + 1 :]):
        return False
    thing = words[1:at] if words[0] in lang.words.np_start else words[:at]
    if any(w in lang.words.any_function_word for w in thing):
        return False  # a clause ("..., he has to fill in the form"), no thing
    return words[at] in before


def _away(lang: Language, text: Text) -> bool:
    """Whether a request only says where not to be ("get out of the way", "move out of my way")."""
    c = lang.derived(_Words)
    words = strip_vocative(lang, strip_politeness(lang, normalise(lang, text)))
    rest = tuple(w for w in words[1:] if w not in c.a_bit)
    return bool(words) and asked_verb(lang, words[0]) in verbs(lang) and rest in c.away


def _one_word(c: _Words, word: str) -> str:
    """The conjunction a chat abbreviation stands for ("n" for "and"), else the word as written."""
    said = c.chat.get(word, (word,))
    return said[0] if len(said) == 1 and said[0] in c.conjunctions else word


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
    """ "the cereals and the milk" -> ["the cereals", "the milk"]; [] when there is no "and". Each
    without its politeness ("the pills please and then the water": "the pills", "the water")."""
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
    out = [tuple(strip_politeness(lang, list(t))) for t in out]
    return out if all(content_words(lang, t) for t in out) else []


def two_named(lang: Language, snapshot: Snapshot, role: str, read: Sequence[Outcome]) -> bool:
    """Whether "X and Y" names a thing each though the whole phrase found one of them ("the
    painkillers and the glass of water": the glass, its words found in the phrase): each part found
    a thing of its own, the whole's among them, and no name of the whole's says "and" itself
    ("the salt and pepper mill"). `read`: the whole phrase's reading, then each part's."""
    whole, *each = [snapshot.get(o.roles.get(role, "")) for o in read]
    ids = {e.id for e in each if e is not None}
    if whole is None or len(ids) < len(each) or whole.id not in ids:
        return False
    return not any(coordinated(lang, tuple(tokens(n))) for n in whole.labels)


def adds_on(lang: Language, words: Words) -> bool:
    """Whether a clause opens with a conjunction, after any politeness ("please and then the glass of
    water"): it adds to the request before it rather than being one of its own."""
    c = lang.derived(_Words)
    for word in words:
        if word in c.conjunctions:
            return True
        if strip_politeness(lang, [word]):
            return False
    return False
