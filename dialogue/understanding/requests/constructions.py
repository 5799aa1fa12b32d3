"""The few requests a frame row cannot say, as small functions the frame table refers to.

Each takes the words as a frame reads them (`Framed`) and returns a `Parse`, or None when it does not
apply (the grammar then tries the next row). Wishes ("I want X", "I want to go to X"), "help me get
to X", "show me the cup" (a question), "greet everyone", "do you like..." (a yes/no question, not an
activity). Needs ("I'm parched") are in `needs`, speech asked for ("tell Ana that...") in `telling`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from dialogue import intents as I
from dialogue.reference.english import Words
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse
from dialogue.understanding.said import Said
from dialogue.understanding.speech.plain import split_at
from dialogue.understanding.tables.prefixes import Prefixes


class ConstructionGrammar:
    """The language's words of the small constructions (made once per language)."""

    def __init__(self, lang: Language) -> None:
        said, closed, words = lang.requests, lang.words, lang.requests.constructions
        #: Prepositions of a place a thing goes, longest first; "to" and "at" say no place to put it
        #: ("goes to town"), only one to take it to after a request to take another thing there.
        self.places = Prefixes(lang.prepositions.longest_first("place"))
        self.not_put = frozenset(lang.prepositions.having("no-put"))
        #: Subjects that never name a thing to put ("I go in the morning", "you belong here").
        self.not_things = words.not_things
        #: "show Ana in", "show them round": the way someone is shown, guiding them.
        self.shown = words.shown
        #: Words that start the clause of a message after the person told ("tell Noor *it*'s time").
        self.subjects = words.subjects
        #: Verbs that follow a subject whatever it is.
        self.verbs_of_any = words.verbs_of_any
        self.needs_doing = words.needs_doing
        self.doing = words.doing
        self.after = words.after
        self.after_ends = sorted(words.after_ends, key=len, reverse=True)
        self.asked_whether = words.asked_whether
        self.asked_of = words.asked_of
        self.asked_not_after = words.asked_not_after
        self.asked_as_you = words.asked_as_you
        self.asked_plain = words.asked_plain
        self.adjuncts = said.all_adjuncts
        self.done = said.done
        self.everyone = said.everyone
        self.goes = Prefixes(said.goes)
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
        self.wants = Prefixes(said.wants)
        self.own_wants, self.own = Prefixes(said.own_wants), said.own
        self.want_verbs = said.want_verbs
        self.their_wants = Prefixes(said.their_wants)
        self.wishers = said.wishers
        self.not_wishers = said.not_wishers
        self.np_start = closed.np_start
        self.function_words = closed.any_function_word
        self.me = closed.me
        self.objects = closed.objects
        self.needy = tuple(sorted(words.needy, key=len, reverse=True))  # (longest first)
        self.going_wants = words.going_wants
        self.going_verbs = words.going_verbs
        self.speakers = words.speakers
        self.a_hand = words.a_hand
        self.a_hand_particles = words.a_hand_particles
        self.enough_lead = words.enough_lead
        self.enough = words.enough
        #: The separators of `split_at`, as it takes them.
        self.helped_to = words.helped_to
        self.copulas = words.copulas
        self.subject_ends = words.subject_ends
        self.quote_skipped = words.quote_skipped
        self.goodbyes = words.goodbyes
        self.goodbye = words.goodbye
        self.telling = words.telling
        self.told_marks = words.told_marks
        self.groups = words.groups


@dataclass(frozen=True)
class Framed:
    """The words as a frame row reads them: its verb phrase and the words after it."""

    #: The language the words are read in.
    lang: Language
    #: The verb phrase's words as the table has them ("pick", "get hold of"; none before any verb is
    #: read).
    verb: Words
    #: The words after the verb phrase (all the words when `verb` is "").
    rest: Words
    #: All the utterance's words, and the original text (for quotes and casing).
    words: Words
    original: Said

    def command(self, intent: str, text: str | None = None, **slots: Words) -> Parse:
        if "recipient" in slots:  # "tell Ana from me that...": whom, not on whose behalf
            slots["recipient"] = _without_adjunct(self.lang.derived(ConstructionGrammar), slots["recipient"])
        return Parse("command", intent, dict(slots), text=text, words=self.words)


def _without_adjunct(c: ConstructionGrammar, words: Words) -> Words:
    """The words without an adjunct at their end ("ana from me", "ana on my behalf")."""
    found = next((a for a in c.adjuncts if len(words) > len(a) and words[-len(a) :] == a), None)
    return words[: -len(found)] if found is not None else words


# -- before any verb: what the whole utterance says ----------------------------------------------
def going(said: Framed) -> Parse | None:
    """ "I want to go to X", "Ellen needs to get to X": take them there."""
    c = said.lang.derived(ConstructionGrammar)
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
    c = said.lang.derived(ConstructionGrammar)
    for lead in c.own_wants.of(said.words):  # "I'll have my cards": only the speaker's own thing
        if said.words[len(lead) : len(lead) + 1] and said.words[len(lead)] in c.own:
            return said.command(I.BRING_OBJECT, object=said.words[len(lead) :], recipient=("me",))
    for lead in c.wants.of(said.words):
        if len(said.words) > len(lead):
            wanted = said.words[len(lead) :]
            if wanted[:1] != ("to",) and wanted[: len(c.a_hand)] != c.a_hand:  # "give me a hand to the door"
                return said.command(I.BRING_OBJECT, object=wanted, recipient=("me",))
    return None


def their_wish(said: Framed) -> Parse | None:
    """ "Ahmed would like the photo album", "he needs his glasses": bring it to them."""
    c = said.lang.derived(ConstructionGrammar)
    w = said.words
    for i in range(1, min(len(w), 4)):
        who = w[:i]
        lead = c.their_wants.first(w, i)
        if lead is None:
            continue
        wanted = w[i + len(lead) :]
        person = who in {(x,) for x in c.wishers} or not set(who) & (c.not_wishers | c.wishers | c.me)
        if person and wanted and wanted[0] != "to":
            return said.command(I.BRING_OBJECT, object=wanted, recipient=_pronoun(c, who))
        return None
    return None


def _pronoun(c: ConstructionGrammar, who: Words) -> Words:
    """ "he", "she", "they" refer to someone the conversation named."""
    said = c.objects.get(who[0]) if len(who) == 1 else None
    return (said,) if said is not None else who


def belonging(said: Framed) -> Parse | None:
    """ "the butter goes back in the fridge", "this belongs on the shelf": put it there."""
    c = said.lang.derived(ConstructionGrammar)
    found = where_it_goes(said.lang, said.words)
    if found is None or found[1] in c.not_put:  # "goes to town" is no place to put it
        return None
    thing, place, where = found
    parse = said.command(I.PLACE_OBJECT, object=thing, recipient=where)
    return replace(parse, marks={"recipient": place})


def where_it_goes(lang: Language, w: Words) -> tuple[Words, Words, Words] | None:
    """ "the butter goes back in the fridge", "the soup goes to table two": the thing, the
    preposition and the place; None when the words say no such thing."""
    c = lang.derived(ConstructionGrammar)
    for i in range(1, min(len(w) - 2, 6)):
        lead = c.goes.first(w, i)
        if lead is None:
            continue
        thing, rest = w[:i], w[i + len(lead) :]
        while rest[:1] and rest[0] in c.goes_particles:
            rest = rest[1:]
        place = c.places.first(rest)
        if place is None or not rest[len(place) :] or thing[0] in c.not_things:
            return None
        return thing, place, rest[len(place) :]
    return None


def enough(said: Framed) -> Parse | None:
    """ "that is enough (now)": stop."""
    c = said.lang.derived(ConstructionGrammar)
    if said.words[: len(c.enough_lead)] == c.enough_lead and set(said.words) & c.enough:
        return said.command(I.STOP_ACTIVITY)
    return None


# -- after a verb ---------------------------------------------------------------------------------
def a_hand(said: Framed) -> Parse | None:
    """ "give George a hand getting to the courtyard" is helping him get there."""
    c = said.lang.derived(ConstructionGrammar)
    rest, hand = said.rest, c.a_hand
    at = next((i for i in range(len(rest) - 1) if rest[i : i + len(hand)] == hand), None)
    if at is None or at == 0:
        return None
    after = rest[at + len(hand) :]
    after = after[1:] if after[:1] and after[0] in c.a_hand_particles else after
    return helping(Framed(said.lang, ("help",), (*rest[:at], *after), said.words, said.original))


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
    found = split_at(said.rest, said.lang.derived(ConstructionGrammar).helped_to)
    if found is None or not found[0] or not found[2]:
        return None
    who = found[0]
    ways = sorted(said.lang.requests.constructions.finding_the_way, key=len, reverse=True)
    way = next((w for w in ways if len(who) > len(w) and who[-len(w) :] == w), ())
    return said.command(I.GUIDE, recipient=who[: len(who) - len(way)], goal=found[2])


def showing(said: Framed) -> Parse | None:
    """ "show me the scissors" asks where they are; "show me the way (to X)" is guiding, and so is
    "show George where the lounge is"."""
    c = said.lang.derived(ConstructionGrammar)
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
    c = said.lang.derived(ConstructionGrammar)
    if said.rest in c.everyone:
        return Parse("greeting", words=said.words, slots={"everyone": said.rest})
    return None


def asking(said: Framed) -> Parse | None:
    """ "do you like music" is a yes/no question, "do the dishes" a request."""
    c = said.lang.derived(ConstructionGrammar)
    if said.rest[:1] and said.rest[0] not in c.done:
        return Parse("unknown", words=said.words)
    return None
