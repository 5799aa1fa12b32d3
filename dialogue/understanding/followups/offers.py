"""Answers to the robot's offer: a yes ("Would you like me to bring you a basket?" "yes please": the
request offered, in the words of the person who accepts it) or a choice among the things offered
("Would you like tea or orange juice?" "I'll have the tea", "the orange juice, ta": the offer made
of the thing chosen). How the robot offers and how a choice is said are `followups.toml`'s
(`offers`, `offers_a_thing`, `choosing`)."""

from __future__ import annotations

from dialogue.history import Utterance
from dialogue.reference.resolution import content_words
from dialogue.understanding.context import Reader
from dialogue.understanding.followups.accepting import accepts
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.said import Said
from dialogue.understanding.speech.plain import expanded, strip_politeness


def offer(reader: Reader, question: Utterance, said: list[str]) -> Outcome | None:
    """ "yes please" to "Would you like me to bring you a basket?": the request the robot offered,
    in the words of the person who accepts it ("bring me a basket")."""
    lang = reader.lexicon.lang
    if not accepts(lang, said):
        return None
    request = _offered(lang, expanded(lang, question.text.rstrip(" ?")))
    outcome = reader.act(parse(lang, " ".join(request), reader.robot_name)) if request else None
    if outcome is None or outcome.intent is None:
        return None
    return outcome.followed_up()


def chosen_offered(reader: Reader, question: Utterance, heard: Said) -> Outcome | None:
    """ "I'll have the tea" to "Would you like tea or orange juice?": the offer made of the one thing
    chosen, when every word naming it was in the offer (None: no offer of things, or a choice of
    something not offered, which is no answer to it)."""
    lang = reader.lexicon.lang
    request = _offered(lang, expanded(lang, question.text.rstrip(" ?")))
    p = parse(lang, " ".join(request), reader.robot_name) if request else None
    offered = p.slots.get("object", ()) if p is not None and p.act == "command" else ()
    if p is None or not offered:
        return None
    said = strip_politeness(lang, expanded(lang, heard), reader.robot_name)
    lead = next((c for c in lang.followups.choosing if tuple(said[: len(c)]) == c), ())
    chosen = tuple(said[len(lead) :])
    named = content_words(lang, chosen)
    if not named or not set(named) <= set(content_words(lang, offered)):
        return None
    outcome = reader.act(p, {"object": chosen})
    return outcome.followed_up() if outcome.intent is not None else None


def _offered(lang: Language, asked: list[str]) -> list[str]:
    """The request an offer makes, in the words of the person offered it ([] when it makes none)."""
    for lead in lang.followups.offers:
        at = next((i for i in range(len(asked)) if tuple(asked[i : i + len(lead)]) == lead), None)
        if at is not None:
            return [lang.followups.swapped.get(w, w) for w in asked[at + len(lead) :]]
    for lead in lang.followups.offers_a_thing:  # "Would you like a towel?"
        if tuple(asked[: len(lead)]) == lead and asked[len(lead) :]:
            return [*lang.followups.offered_request, *asked[len(lead) :]]
    return []
