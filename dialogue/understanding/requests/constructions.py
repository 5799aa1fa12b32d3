"""The few requests a frame row cannot say, as small functions the frame table refers to.

Each takes the words as a frame reads them (`Framed`) and returns a `Parse`, or None when it does not
apply (the grammar then tries the next row). Quoted speech, needs ("I'm parched"), wishes ("I want
X", "I want to go to X"), "help me get to X", "show me the cup" (a question), "greet everyone", "do
you like..." (a yes/no question, not an activity).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from lemminflect import getLemma

from dialogue import intents as I
from dialogue.reference.english import Words
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse
from dialogue.understanding.said import Said
from dialogue.understanding.speech.clauses import finite
from dialogue.understanding.speech.plain import QUOTED, expanded, message, original_text, split_at, starts


class _Words:
    """The language's words of the small constructions (made once per language)."""

    def __init__(self, lang: Language) -> None:
        said, closed, words = lang.requests, lang.words, lang.requests.constructions
        #: Prepositions of a place a thing goes, longest first; "to" and "at" say no place to put it
        #: ("goes to town"), only one to take it to after a request to take another thing there.
        self.places = lang.prepositions.longest_first("place")
        self.not_put = frozenset(lang.prepositions.having("no-put"))
        #: Subjects that never name a thing to put ("I go in the morning", "you belong here").
        self.not_things = words.not_things
        #: "show Ana in", "show them round": the way someone is shown, guiding them.
        self.shown = words.shown
        #: Words that start the clause of a message after the person told ("tell Noor *it*'s time").
        self.subjects = words.subjects
        #: Verbs that follow a subject whatever it is.
        self.verbs_of_any = words.verbs_of_any
        self.adjuncts = said.all_adjuncts
        self.done = said.done
        self.everyone = said.everyone
        self.goes = said.goes
        self.goes_particles = said.goes_particles
        self.intensifiers = said.intensifiers
        self.needs = said.needs
        self.available = sorted(words.available, key=len, reverse=True)
        self.available_ends = words.available_ends
        self.anything = words.anything
        self.asking = frozenset(w for lead in words.available for w in lead)
        self.someone_is = frozenset((w,) for w in words.someone_is)
        self.for_whom = frozenset((w,) for w in lang.prepositions.words("terse-to"))
        self.personal = closed.personal
        self.wants = said.wants
        self.want_verbs = said.want_verbs
        self.their_wants = said.their_wants
        self.wishers = said.wishers
        self.not_wishers = said.not_wishers
        self.np_start = closed.np_start
        self.function_words = closed.any_function_word
        self.me = closed.me
        self.objects = closed.objects
        self.needy = words.needy
        self.going_wants = words.going_wants
        self.going_verbs = words.going_verbs
        self.speakers = words.speakers
        self.a_hand = words.a_hand
        self.a_hand_particles = words.a_hand_particles
        self.enough_lead = words.enough_lead
        self.enough = words.enough
        #: The separators of `split_at`, as it takes them.
        self.helped_to = [" ".join(p) for p in words.helped_to]
        self.copulas = words.copulas
        self.subject_ends = words.subject_ends
        self.quote_skipped = words.quote_skipped
        self.goodbyes = words.goodbyes
        self.goodbye = words.goodbye
        self.telling = words.telling
        self.told_marks = [" ".join(p) for p in words.told_marks]
        self.groups = words.groups


@dataclass(frozen=True)
class Framed:
    """The words as a frame row reads them: its verb phrase and the words after it."""

    #: The language the words are read in.
    lang: Language
    #: The verb phrase as the table has it ("pick", "get hold of"; "" before any verb is read).
    verb: str
    #: The words after the verb phrase (all the words when `verb` is "").
    rest: Words
    #: All the utterance's words, and the original text (for quotes and casing).
    words: Words
    original: Said

    def command(self, intent: str, text: str | None = None, **slots: Words) -> Parse:
        if "recipient" in slots:  # "tell Ana from me that...": whom, not on whose behalf
            slots["recipient"] = _without_adjunct(self.lang.derived(_Words), slots["recipient"])
        return Parse("command", intent, dict(slots), text=text, words=self.words)


def _without_adjunct(c: _Words, words: Words) -> Words:
    """The words without an adjunct at their end ("ana from me", "ana on my behalf")."""
    found = next((a for a in c.adjuncts if len(words) > len(a) and words[-len(a) :] == a), None)
    return words[: -len(found)] if found is not None else words


# -- before any verb: what the whole utterance says ----------------------------------------------
def need(said: Framed) -> Parse | None:
    """ "I'm really parched", "we are starving": something of the class that meets the need."""
    c = said.lang.derived(_Words)
    w = said.words
    whose: Words = ("me",)
    if w[:2] in c.needy:
        w = w[2:]
    elif _someone(c, w[:1]) and w[1:2] in c.someone_is:  # "Ruby is thirsty"
        whose, w = w[:1], w[2:]
    elif w[:1] and _someone(c, (w[0].removesuffix("'s"),)) and w[0].endswith("'s"):  # "Ruby's thirsty"
        whose, w = (w[0].removesuffix("'s"),), w[1:]
    else:
        return None
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


def _someone(c: _Words, words: Words) -> bool:
    """Whether a word alone may be who has a need ("Ruby"): no function word."""
    return len(words) == 1 and words[0] not in c.function_words


def _qualifiers(said: Framed, words: Words) -> Words:
    """The words that say which of what meets a need is asked for ("sugar free" of "anything sugar
    free to drink"), without the purpose after them ("to drink")."""
    requests = said.lang.requests
    at = next((i for i in range(len(words)) if requests.purpose(words[i:]) is not None), len(words))
    return words[:at]


def _available(c: _Words, words: Words) -> Words:
    """What a question of what there is asks about ("is there any juice", "any tea going"); ()
    when the words are no such question."""
    lead = next((a for a in c.available if words[: len(a)] == a), None)
    if lead is None:
        return ()
    asked = words[len(lead) :]
    while asked and asked[-1] in c.available_ends:
        asked = asked[:-1]
    return asked


def going(said: Framed) -> Parse | None:
    """ "I want to go to X", "Ellen needs to get to X": take them there."""
    c = said.lang.derived(_Words)
    w = said.words
    for i in range(len(w) - 4):
        wants = w[i] in c.want_verbs or w[i : i + 2] in c.going_wants
        at = i + (2 if w[i] == "would" else 1)
        goes = w[at : at + 1] == ("to",) and at + 1 < len(w) and w[at + 1] in c.going_verbs
        if wants and goes and w[at + 2 : at + 3] == ("to",) and w[at + 3 :]:
            who = w[:i]
            mine = not who or (len(who) == 1 and who[0] in c.speakers)
            return said.command(I.GUIDE, recipient=("me",) if mine else who,
                                goal=w[at + 3 :])  # fmt: skip
    return None


def wanting(said: Framed) -> Parse | None:
    """ "I would like the apple", "can I have a tea": bring it to the speaker."""
    c = said.lang.derived(_Words)
    for lead in c.wants:
        if starts(said.words, lead) and len(said.words) > len(lead):
            wanted = said.words[len(lead) :]
            if wanted[:1] != ("to",) and wanted[: len(c.a_hand)] != c.a_hand:  # "give me a hand to the door"
                return said.command(I.BRING_OBJECT, object=wanted, recipient=("me",))
    return None


def their_wish(said: Framed) -> Parse | None:
    """ "Ahmed would like the photo album", "he needs his glasses": bring it to them."""
    c = said.lang.derived(_Words)
    w = said.words
    for i in range(1, min(len(w), 4)):
        who = w[:i]
        lead = next((p for p in c.their_wants if w[i : i + len(p)] == p), None)
        if lead is None:
            continue
        wanted = w[i + len(lead) :]
        person = who in {(x,) for x in c.wishers} or not set(who) & (c.not_wishers | c.wishers | c.me)
        if person and wanted and wanted[0] != "to":
            return said.command(I.BRING_OBJECT, object=wanted, recipient=_pronoun(c, who))
        return None
    return None


def _pronoun(c: _Words, who: Words) -> Words:
    """ "he", "she", "they" refer to someone the conversation named."""
    said = c.objects.get(who[0]) if len(who) == 1 else None
    return (said,) if said is not None else who


def belonging(said: Framed) -> Parse | None:
    """ "the butter goes back in the fridge", "this belongs on the shelf": put it there."""
    c = said.lang.derived(_Words)
    found = where_it_goes(said.lang, said.words)
    if found is None or found[1] in c.not_put:  # "goes to town" is no place to put it
        return None
    thing, place, where = found
    parse = said.command(I.PLACE_OBJECT, object=thing, recipient=where)
    return replace(parse, marks={"recipient": " ".join(place)})


def where_it_goes(lang: Language, w: Words) -> tuple[Words, Words, Words] | None:
    """ "the butter goes back in the fridge", "the soup goes to table two": the thing, the
    preposition and the place; None when the words say no such thing."""
    c = lang.derived(_Words)
    for i in range(1, min(len(w) - 2, 6)):
        lead = next((p for p in c.goes if w[i : i + len(p)] == p), None)
        if lead is None:
            continue
        thing, rest = w[:i], w[i + len(lead) :]
        while rest[:1] and rest[0] in c.goes_particles:
            rest = rest[1:]
        place = next((p for p in c.places if rest[: len(p)] == p), None)
        if place is None or not rest[len(place) :] or thing[0] in c.not_things:
            return None
        return thing, place, rest[len(place) :]
    return None


def enough(said: Framed) -> Parse | None:
    """ "that is enough (now)": stop."""
    c = said.lang.derived(_Words)
    if said.words[: len(c.enough_lead)] == c.enough_lead and set(said.words) & c.enough:
        return said.command(I.STOP_ACTIVITY)
    return None


# -- after a verb ---------------------------------------------------------------------------------
def a_hand(said: Framed) -> Parse | None:
    """ "give George a hand getting to the courtyard" is helping him get there."""
    c = said.lang.derived(_Words)
    rest, hand = said.rest, c.a_hand
    at = next((i for i in range(len(rest) - 1) if rest[i : i + len(hand)] == hand), None)
    if at is None or at == 0:
        return None
    after = rest[at + len(hand) :]
    after = after[1:] if after[:1] and after[0] in c.a_hand_particles else after
    return helping(Framed(said.lang, "help", (*rest[:at], *after), said.words, said.original))


def company(said: Framed) -> Parse | None:
    """ "keep Edith company (for ten minutes)": engaging with her; anything else kept is no request."""
    rest = said.rest
    at = next((i for i, w in enumerate(rest) if w == "company"), None)
    if not at or (rest[at + 1 :] and rest[at + 1] != "for"):  # (how long changes nothing)
        return None
    return said.command(I.ENGAGE_WITH, recipient=rest[:at])


def helping(said: Framed) -> Parse | None:
    """ "help me get to the bathroom", "help Ana find the way to the exit": take them there (the
    way said after the person is no part of their name)."""
    found = split_at(said.rest, said.lang.derived(_Words).helped_to)
    if found is None or not found[0] or not found[2]:
        return None
    who = found[0]
    ways = sorted(said.lang.requests.constructions.finding_the_way, key=len, reverse=True)
    way = next((w for w in ways if len(who) > len(w) and who[-len(w) :] == w), ())
    return said.command(I.GUIDE, recipient=who[: len(who) - len(way)], goal=found[2])


def showing(said: Framed) -> Parse | None:
    """ "show me the scissors" asks where they are; "show me the way (to X)" is guiding, and so is
    "show George where the lounge is"."""
    c = said.lang.derived(_Words)
    if "where" in said.rest[1:]:
        at = said.rest.index("where")
        place = said.rest[at + 1 :]
        place = place[:-1] if place[-1:] and place[-1] in c.copulas else place
        return said.command(I.GUIDE, recipient=said.rest[:at] or ("me",), goal=place) if place else None
    if "way" in said.rest or "to" in said.rest or set(said.rest[-1:]) & c.shown:
        return None  # ("show Ana out": guiding her, not where she is)
    thing = said.rest[1:] if said.rest[:1] and said.rest[0] in c.me else said.rest
    return Parse("question", question="where", slots={"thing": thing}, words=said.words)




def everyone(said: Framed) -> Parse | None:
    """ "greet everyone": no one recipient, a greeting said aloud."""
    c = said.lang.derived(_Words)
    if said.rest in c.everyone:
        return Parse("greeting", words=said.words, slots={"everyone": said.rest})
    return None


def asking(said: Framed) -> Parse | None:
    """ "do you like music" is a yes/no question, "do the dishes" a request."""
    c = said.lang.derived(_Words)
    if said.rest[:1] and said.rest[0] not in c.done:
        return Parse("unknown", words=said.words)
    return None


def letting_know(said: Framed) -> Parse | None:
    """ "let Tom know that dinner is ready" is "tell Tom that...". """
    if "know" not in said.rest:
        return None
    told = tuple(x for x in said.rest if x != "know")
    return speech(Framed(said.lang, "tell", told, said.words, said.original))


def _plural(word: str) -> bool:
    """Whether a noun is a plural ("kids", "children")."""
    lemmas = getLemma(word, "NOUN")
    return bool(lemmas) and lemmas[0] != word




def _clause_start(c: _Words, rest: Words) -> int | None:
    """Where a clause with a subject of its own starts after the person told, if one does: a subject
    pronoun ("tell Noor *it*'s time"), or a noun phrase and its verb ("tell Kasia *her courgettes
    are* ready", "tell Ana *the taxi is* here")."""
    starts = (i for i in range(1, len(rest) - 1) if rest[i] in c.subjects or _subject_phrase(c, rest, i))
    return next(starts, None)




#: At most this many words of a subject before its verb ("the customer for the grey car has...").
_SUBJECT_WORDS = 6


def _subject_phrase(c: _Words, rest: Words, i: int) -> bool:
    """Whether a noun phrase starts at i and its verb follows it ("her courgettes are", "the film
    starts", "the customer for the grey car has")."""
    if (rest[i] not in c.np_start and rest[i] != "her") or i + 1 >= len(rest):
        return False
    if rest[i + 1] in c.function_words:
        return False
    for k in range(i + 2, min(len(rest), i + 1 + _SUBJECT_WORDS)):
        if rest[k] in c.verbs_of_any or finite(rest[k], third_person=True):
            return True
        if rest[k] in c.subject_ends:
            return False
    return False


def speech(said: Framed) -> Parse:
    """What to say, to whom: quoted words kept as they are, "tell X that/to...", "say X to Y"."""
    c = said.lang.derived(_Words)
    verb, rest, original = said.verb, said.rest, said.original
    quoted = QUOTED.search(original.text)
    if quoted:
        # The quoted words are the text; the recipient is found outside the quotes only.
        outside = expanded(said.lang, original.text[: quoted.start()] + " " + original.text[quoted.end() :])
        rest = tuple(outside[outside.index(verb) + 1 :]) if verb in outside else ()
        rest = tuple(x for x in rest if x not in c.quote_skipped)
        recipient = rest[1:] if rest[:1] == ("to",) else rest
        return said.command(I.SAY, text=quoted.group(1).strip(), recipient=recipient)
    unknown = Parse("unknown", words=(verb, *rest))
    if rest[:1] and rest[0] in c.goodbyes and "to" in rest:
        return said.command(I.SAY, text=c.goodbye, recipient=rest[rest.index("to") + 1 :])
    if verb in c.telling:
        found = split_at(rest, c.told_marks)
        clause = _clause_start(c, rest) if verb != "ask" else None
        if clause is not None and (found is None or clause < len(found[0])):
            # "tell Noor it's time to go": the message is a clause of its own, its "to" is its own
            found = rest[:clause], "", rest[clause:]
        if found is not None:
            recipient, sep, text = found
            text = ("please", *text) if sep == "to" else text
            if sep == "about" or (verb == "ask" and sep != "to"):
                return unknown
        elif verb == "ask":  # "ask Ana if she wants tea": a question to put, not words to say
            return unknown
        else:  # "tell Maria", "tell my mum": a name, or a determiner and its noun
            n = 2 if rest[:1] and rest[0] in c.np_start else 1
            recipient, text = rest[:n], rest[n:]
        if recipient[:1] and recipient[0] in c.me:  # "tell me a joke": small talk, not a SAY intent
            return unknown
        if len(recipient) == 2 and recipient[0] in c.groups and _plural(recipient[1]):
            return unknown  # "tell the kids": several people, whom one intent cannot say

        if not text:  # "tell Maria": the interpreter asks what to say
            return said.command(I.SAY, recipient=recipient)
        words = message(said.lang, original, text[1:] if text[0] == "please" else text)
        said_text = f"please {words}" if text[0] == "please" else words
        return said.command(I.SAY, text=said_text, recipient=recipient)
    if rest[:1] == ("to",):  # "say to Sandeep that the film starts soon": to whom, then what
        return _said_to(said, rest[1:])
    found = split_at(rest, ["to"])
    text_words, recipient = (found[0], found[2]) if found is not None else (rest, ())
    if not text_words:
        return unknown
    return said.command(I.SAY, text=original_text(said.lang, original, text_words), recipient=recipient)


def _said_to(said: Framed, rest: Words) -> Parse:
    """ "(say) to Sandeep that the film starts soon", "(say) to Ana it's time": the person, then the
    message ("that" or a clause of its own starts it)."""
    found = split_at(rest, ["that"])
    clause = _clause_start(said.lang.derived(_Words), rest)
    if found is not None and (clause is None or len(found[0]) <= clause):
        recipient, text = found[0], found[2]
    elif clause is not None:
        recipient, text = rest[:clause], rest[clause:]
    else:
        return Parse("unknown", words=said.words)
    if not text:
        return said.command(I.SAY, recipient=recipient)
    return said.command(I.SAY, text=message(said.lang, said.original, text), recipient=recipient)
