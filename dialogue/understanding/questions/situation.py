"""The reader of questions about the situation ("where is my mug?", "what do you see?", "what's your
name?"): what the question is about, grounded in its turn, then answered by its kind's row of
`QUESTIONS` (the grammar's `question`, dialogue.understanding.questions.grammar)."""

from __future__ import annotations

from collections.abc import Callable

from dialogue.reference.antecedent import antecedent, pronoun_kinds
from dialogue.reference.english import Words, tokens
from dialogue.reference.resolution import (
    ANYWHERE,
    PERSON,
    content_words,
    is_pronoun,
    resolve,
)
from dialogue.understanding.context import Context, Reader
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.questions import answers, presence, recalled
from dialogue.understanding.questions import placed as placed_at
from dialogue.understanding.replies import say

#: The questions whose subject may be a pronoun or someone spoken of ("where is she").
_ABOUT = frozenset({"where", "can_see", "what_is", "what_on", "whose", presence.ARRIVED, presence.DEPARTED})

#: One kind of question answered: the turn, what it is about, whose that is, and the parse.
Answer = Callable[[Reader, Words, str | None, Parse], Outcome]


def _what_see(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return Outcome(answers.what_do_you_see(c.lang, c.snapshot, c.speaker))


def _who_see(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    # "who else lives here", "who am I": a verb besides being and seeing asks something else ("who
    # else is down the allotment": a place the KB may not name, still who is there)
    if any(not c.lexicon.knows(w) and "VERB" in lemmas_of(w) for w in p.slots.get("rest", ())):
        return _no_answer(c)
    return Outcome(answers.who_do_you_see(c.lang, c.snapshot, c.speaker))


def _where(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return Outcome(answers.where_is(c.lexicon, thing, c.speaker, owner))


def _what_on(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    asked = " ".join(p.slots.get("relation", ()))
    reply, clarify = answers.what_is_on(c.lexicon, thing, asked)
    return Outcome(reply, clarify=clarify)


def _which_on(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    asked = " ".join(p.slots.get("relation", ()))
    found = answers.which_are_on(c.lexicon, thing, p.slots.get("place", ()), asked)
    if found is None:
        return _no_answer(c)
    return Outcome(found[0], clarify=found[1])


def _who_in(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    reply, clarify = answers.who_is_in(c.lexicon, thing, c.speaker)
    return Outcome(reply, clarify=clarify)


def _what_near(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    reply, clarify = answers.what_is_near(c.lexicon, thing, p.slots.get("relation", ()))
    return Outcome(reply, clarify=clarify)


def _can_see(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    locatives = c.lang.derived(_Locatives).said
    placed = placed_at.is_there(c.lexicon, thing, c.speaker, locatives) if owner is None else None
    return Outcome(placed or answers.can_you_see(c.lexicon, thing, c.speaker, owner))


class _Locatives:
    """The prepositions a question puts someone somewhere with ("is Marcus *in* the kitchen")."""

    def __init__(self, lang: Language) -> None:
        self.said = lang.prepositions.having("asked-on")


def _what_is(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return Outcome(answers.what_is(c.lexicon, thing, c.speaker, owner))


def _which_see(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return Outcome(answers.which_do_you_see(c.lexicon, thing))


def _how_many(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    said = set(content_words(c.lang, thing))
    if said and said <= c.lang.questions.situation.someone:  # "how many people": who is seen
        return Outcome(answers.how_many_people(c.lang, c.snapshot, c.speaker))
    return Outcome(answers.how_many(c.lexicon, thing))


def _colour(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return Outcome(answers.colour_of(c.lexicon, thing, c.speaker, owner))


def _whose(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return Outcome(answers.whose(c.lexicon, thing, c.speaker, owner))


def _presence(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    came = presence.answer(c.lexicon, thing, c.speaker, p.question or "")
    return Outcome(came) if came is not None else _no_answer(c)


def _asked_for(r: Reader, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return recalled.asked_for(r)


def _untracked(r: Reader, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return recalled.untracked(r)


def _name(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return Outcome(say(c.lang, "social.robot_name", name=c.robot_name))


def _how_are_you(c: Context, thing: Words, owner: str | None, p: Parse) -> Outcome:
    return Outcome(say(c.lang, "social.fine"))


#: Each kind of question and its answer (a kind not here has none).
QUESTIONS: dict[str, Answer] = {
    "what_see": _what_see, "who_see": _who_see, "where": _where, "what_on": _what_on,
    "which_on": _which_on, "who_in": _who_in, "what_near": _what_near, "can_see": _can_see,
    "what_is": _what_is,
    "which_see": _which_see, "how_many": _how_many, "colour": _colour, "whose": _whose,
    "name": _name, "how_are_you": _how_are_you, presence.ARRIVED: _presence, presence.DEPARTED: _presence,
    "asked_for": _asked_for, "untracked": _untracked,
}  # fmt: skip


def answer(c: Reader, p: Parse) -> Outcome:
    """The answer to a question about the situation, or the reply that says there is none."""
    thing = p.slots.get("thing", ()) or p.slots.get("place", ())
    said = content_words(c.lang, thing)
    # "where is she": a person a question may be about ("do you know where she is")
    someone = set(said) <= c.lang.questions.situation.someone_said and bool(said)
    if p.question in _ABOUT and (is_pronoun(c.lang, thing) or someone):
        kinds = PERSON if someone else pronoun_kinds(c.lang, thing, ANYWHERE)  # "it" is no one
        ref = antecedent(c.lexicon, c.history, kinds, speaker=c.speaker)
        if ref is None:  # "where did you put it" with nothing spoken of: what "it" is, a model may know
            return _no_answer(c)
        thing = tuple(tokens(ref.id))
    _, owner = c.refs.possessive(thing, p.slots)  # "where is my mug": the speaker's
    content = content_words(c.lang, thing)
    unsure = c.refs.half_known(content) or c.refs.strange(content)  # "how many bks": a doubt
    if content and unsure and not resolve(c.lexicon, thing, ANYWHERE).matches:
        return _no_answer(c)
    reply = QUESTIONS.get(p.question or "")
    return reply(c, thing, owner, p) if reply is not None else _no_answer(c)


def _no_answer(c: Context) -> Outcome:
    return Outcome(say(c.lang, "sorry.no_answer"), understood=False)
