"""Whether the robot has a skill for an activity it is asked to do ("tidy the shelves", "play a
game"), or says it cannot ("fold the towels", "iron the bathrobe", "play us something on the piano",
"do my exercises for me"): which activities are the robot's is the language's data
(`requests.toml`: `skill_verbs`, `skills`, `starting`)."""

from __future__ import annotations

from dialogue import intents as I
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.replies import said_back, say


def skilled(lang: Language, p: Parse) -> bool:
    """Whether an activity asked for is one the robot can do: asked to start (any), said by a verb
    of its chores, or named by a word of its activities that is not said to be the speaker's own."""
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


def unskilled(lang: Language, p: Parse) -> Outcome | None:
    """ "Fold all the towels for me": the robot says it cannot, and starts nothing; None when the
    request is not an activity beyond its skills. The rules do not claim to have understood it: the
    words may say what they cannot read ("water jug to Edith"), which a model behind them may."""
    if skilled(lang, p):
        return None
    return Outcome(say(lang, "request.cannot", action=said_back(lang, p.words)), understood=False)
