"""Whether the robot has a skill for what it is asked to do ("tidy the shelves", "play a game"), or
says it cannot: an activity beyond it ("fold the towels", "iron the bathrobe", "play us something on
the piano", "do my exercises for me"), a thing fixed to a wall or a ceiling rather than put there
("hang the calendar on the wall"), or an action it has no intent for, said alone ("plug the lamp
in", "pin the calendar up"). Which activities are the robot's, what things are fixed to and which
actions it has no intent for are the language's data (`requests.toml`: `skill_verbs`, `skills`,
`starting`, `fixtures`, `no_intent_verbs`)."""

from __future__ import annotations

from dialogue import intents as I
from dialogue.reference.resolution import content_words
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.replies import said_back, say


def skilled(lang: Language, p: Parse) -> bool:
    """Whether what is asked for is one the robot can do: no placing on a fixture, and an activity
    asked to start (any), said by a verb of its chores, or named by a word of its activities that is
    not said to be the speaker's own."""
    if p.intent == I.PLACE_OBJECT:
        return not _on_fixture(lang, p)
    said = p.slots.get("activity")
    if p.intent != I.START_ACTIVITY or said is None or not p.words:
        return True
    r = lang.requests
    verb = p.words[0]
    # "vacuuming the floor please": the verb's lemma is the skill's ("vacuum")
    if any(v in r.starting or v in r.skill_verbs for v in (verb, *lemmas_of(verb).get("VERB", ()))):
        return True
    # "do my / our / her exercises for me": someone else's to do; "do your exercises": the robot's
    owned = {w for key, w in lang.words.owners.items() if key != "yours"}
    theirs = bool(said[:1]) and said[0] in owned
    words = p.words
    named = any(words[i : i + len(s)] == s for s in r.skills for i in range(len(words)))
    return named and not theirs


def _on_fixture(lang: Language, p: Parse) -> bool:
    """Whether the place of a placing is one things are fixed to ("hang the calendar on the wall"):
    its head is a fixture ("on the shelf by the wall" is the shelf's) and the thing is attached to
    it, by the preposition or by the verb ("put the watering can by the wall" is a placing)."""
    place = tuple(p.slots.get("recipient", ()))
    cut = next((i for i, w in enumerate(place) if w in lang.modifier_start), len(place))
    head = content_words(lang, place[:cut])
    if not head or head[-1] not in lang.requests.fixtures:
        return False
    verb = p.words[:1]
    hung = bool(verb) and bool({verb[0], *lemmas_of(verb[0]).get("VERB", ())} & lang.requests.hanging)
    return hung or _attached(lang, p.words, place)


def _attached(lang: Language, words: tuple[str, ...], place: tuple[str, ...]) -> bool:
    """Whether the place is said after a preposition that attaches ("to the ceiling"), where the
    words say it last."""
    at = next((i for i in range(len(words) - len(place), -1, -1) if words[i : i + len(place)] == place), None)
    if at is None:
        return False
    return any(words[:at][-len(a) :] == a for a in lang.prepositions.having("attaches"))


def unskilled(lang: Language, p: Parse) -> Outcome | None:
    """ "Fold all the towels for me": the robot says it cannot, and starts nothing; None when the
    request is not beyond its skills. The rules do not claim to have understood it: the words may
    say what they cannot read ("water jug to Edith"), which a model behind them may."""
    if skilled(lang, p):
        return None
    return Outcome(say(lang, "request.cannot", action=said_back(lang, p.words)), understood=False)


def no_intent(lang: Language, p: Parse) -> Outcome | None:
    """ "Plug the lamp in": a request no frame reads whose verb is an action the robot has no intent
    for is said to be beyond it, not misunderstood; None for any other words."""
    if p.act != "unknown" or len(p.words) < 2:
        return None
    verb = p.words[0]
    if not {verb, *lemmas_of(verb).get("VERB", ())} & lang.requests.no_intent_verbs:
        return None
    return Outcome(say(lang, "request.cannot", action=said_back(lang, p.words)), understood=False)
