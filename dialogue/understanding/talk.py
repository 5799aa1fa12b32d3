"""Social talk: the acts of the grammar that are neither a request nor a question about the
situation, each answered by its row of `TALK` ("hello", "thanks", "bye", "what can you do?", "tell
me a joke", "don't go", "if Ana comes, ...").

A greeting is the one that acts (greeting the speaker, or everyone verbally only); a farewell ends
the conversation; a request negated or under a condition yet to happen is not done now; "never
mind" just after the robot took on a request stops it.
"""

from __future__ import annotations

from collections.abc import Callable

from dialogue import intents as I
from dialogue.reference.english import Words
from dialogue.reference.resolution import PERSON, resolve
from dialogue.understanding.context import Context
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.replies import abilities, acknowledgement, goodbye, hello, say
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.requests.vocabulary import Grammar
from dialogue.understanding.said import Said


def greeting(c: Context, p: Parse, overrides: dict[str, Words]) -> Outcome:
    if "everyone" in p.slots:  # no single recipient: greet verbally only
        return Outcome(say(c.lang, "social.hello_everyone"))
    return Outcome(hello(c.lang, c.snapshot, c.speaker), I.GREET, {"recipient": c.speaker})


def _negated(c: Context, p: Parse, overrides: dict[str, Words]) -> Outcome:
    if p.words in c.lang.speech.cancels and _acting(c):  # "actually, never mind" to "Getting it now."
        roles: dict[str, str] = {}
        return Outcome(acknowledgement(c.lang, c.snapshot, c.speaker, I.STOP_ACTIVITY, roles, {}),
                       I.STOP_ACTIVITY, roles)  # fmt: skip
    return Outcome(say(c.lang, "social.wont"))


def _acting(c: Context) -> bool:
    """Whether the robot's last words took on a request the speaker made just before them (it said
    no question): what it may be doing now."""
    said = c.history[-2:]
    if len(said) < 2 or said[0].role != "user" or said[1].role == "user":
        return False
    if said[1].text.rstrip().endswith("?"):
        return False
    asked = parse(c.lang, Said.read(c.lang, said[0].text), c.robot_name)
    return asked.act == "command" and asked.intent is not None


def _conditional(c: Context, p: Parse, overrides: dict[str, Words]) -> Outcome:
    # the rules act now or never: asked again, then
    awaited = _awaited(c, p.words)
    if awaited is not None:  # "When Kwame gets here, ...": whom the robot cannot wait for
        return Outcome(say(c.lang, "social.later_someone", name=c.snapshot.name_of(awaited)))
    return Outcome(say(c.lang, "social.later"))


def _awaited(c: Context, words: Words) -> str | None:
    """The person a condition waits for, named first in it ("when Marta's back", "once Ana arrives",
    "if Declan comes by"), if the KB knows them."""
    said = c.lang.derived(Grammar).conditions.first(words)
    said = words[:1] if said is None else said  # (the first word, else: "if")
    first = words[len(said) : len(said) + 1]
    if not first or not _arrives(c, words[len(said) + 1 :]):
        return None  # ("when Carol leaves": no one to wait for)
    person = resolve(c.lexicon, first, PERSON).one
    return person.id if person is not None and person.id != c.speaker else None


def _arrives(c: Context, rest: Words) -> bool:
    """Whether the words after a person say they arrive ("gets here", "arrives", "'s back")."""
    said = (rest[0], *lemmas_of(rest[0]).get("VERB", ())) if rest else ()
    return any(a[0] in said and rest[1 : len(a)] == a[1:] for a in c.lang.requests.arrivals)


def _thanks(c: Context, p: Parse, overrides: dict[str, Words]) -> Outcome:
    return Outcome(say(c.lang, "social.welcome"))


def _farewell(c: Context, p: Parse, overrides: dict[str, Words]) -> Outcome:
    return Outcome(goodbye(c.lang, c.snapshot, c.speaker), farewell=True)


def _abilities(c: Context, p: Parse, overrides: dict[str, Words]) -> Outcome:
    return Outcome(abilities(c.lang))


def _joke(c: Context, p: Parse, overrides: dict[str, Words]) -> Outcome:
    return Outcome(say(c.lang, "social.no_jokes"))


#: How each act of social talk is answered.
TALK: dict[str, Callable[[Context, Parse, dict[str, Words]], Outcome]] = {
    "greeting": greeting, "negated": _negated, "conditional": _conditional, "thanks": _thanks,
    "farewell": _farewell, "abilities": _abilities, "joke": _joke,
}  # fmt: skip
