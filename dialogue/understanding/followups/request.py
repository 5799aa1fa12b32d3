"""Answers to the robot's last question: a fragment that completes the pending request ("the red
one", "mine, obviously", "the pink one, it's Carla's"), a yes or a no to "Do you mean the flat
brush?", a yes to an offer ("Would you like me to bring you a basket?" "yes please") and "both" to
"Which mug do you mean...?"; and the same request for another thing ("and the soup goes to table
two" after "take the steak to table four"). A correction of the request just made is `correction`'s.

The robot's question must be the latest utterance (system notes aside); a fragment or a confirmation
re-reads the request said right before it, an accepted offer is read as the request the robot made.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.reference.clarify import describe_options
from dialogue.reference.english import Words, tokens
from dialogue.reference.facts import RELATIONS
from dialogue.reference.resolution import ROLE_KINDS, content_words, resolve
from dialogue.schema import FREE_FORM_OBJECT
from dialogue.understanding.context import Reader
from dialogue.understanding.followups import proposal
from dialogue.understanding.followups.accepting import accepts
from dialogue.understanding.followups.correction import correction
from dialogue.understanding.followups.offers import chosen_offered, offer
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.replies import say, then
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.requests.constructions import where_it_goes
from dialogue.understanding.said import Said
from dialogue.understanding.speech.clauses import clauses, described, description
from dialogue.understanding.speech.plain import expanded, plain, strip_politeness


def follow_up(reader: Reader, p: Parse, heard: Said) -> Outcome | None:
    """What the words answer of the robot's last question, or None when they answer none."""
    spoken = [i for i, u in enumerate(reader.history) if u.role != "system"]
    if not spoken:
        return None
    question = reader.history[spoken[-1]]
    asked = _question_asked(question.text)
    if question.role != "assistant" or asked is None:
        return None
    question = replace(question, text=asked)  # ("Teodor is outside. Shall I take it there?")
    lang = reader.lexicon.lang
    answer = [lang.followups.no.get(w, w) for w in expanded(lang, heard)]
    said = [w for w in answer if w != "no"]
    confirmed = proposal.answered(reader, answer)
    if confirmed is not None:  # "yes" or "no" to "Shall I bring the soap to Jordan?"
        return confirmed
    accepted = (offer(reader, question, said) or chosen_offered(reader, question, heard)
                or reaffirmed(reader, spoken, question, answer))
    if accepted is not None:
        return accepted
    found = _pending(reader, spoken, heard)
    if found is None:
        return None
    before, pending = found
    earlier = reader.within(reader.history[:before])
    first = earlier.act(pending)
    if first.open_role is None:
        return None
    confirmed = confirmation(earlier, pending, first, question, answer)
    if confirmed is not None:
        return confirmed.followed_up()
    if tuple(said) in lang.followups.both:
        return _every(earlier, pending, first, question.text)
    fragment, more = _fragment(lang, p, heard)
    if not fragment:
        return None
    chosen = _chosen(earlier, pending, first, fragment) if more is None else None
    if chosen is not None:
        return chosen
    merged = _merged(lang, fragment, first)
    if more is not None:  # "the pink one, it's Carla's"
        merged = described(lang, merged, more)
    role = first.open_role
    if role == "object" and pending.intent in FREE_FORM_OBJECT:  # "What should I say?" "Dinner is ready"
        pending = replace(pending, text=heard.text.strip().rstrip(".!?").strip() or None)
    outcome = earlier.act(pending, {role: merged})
    if outcome.intent is None and not outcome.clarify:
        return None
    return _asked_again(reader, fragment, outcome) if outcome.clarify else outcome.followed_up()


def _question_asked(text: str) -> str | None:
    """The question the robot's words ask: the last of its sentences that ends with a question mark
    ("Do you mean Sofia's phone? Yours is in the hallway." asks the first), None when none does.
    Another system's robot may say more than the question; the answer answers the question."""
    sentences, start = [], 0
    for at, mark in enumerate(text):
        if mark in ".!?" and (at + 1 == len(text) or text[at + 1].isspace()):
            sentences.append(text[start : at + 1].strip())
            start = at + 1
    return next((s for s in reversed(sentences) if s.endswith("?")), None)


def _asked_again(reader: Reader, fragment: Words, outcome: Outcome) -> Outcome:
    """An answer that leaves the question open: "the left one" (the KB says nothing of left and
    right) is said so and asked again; "the flowery one" to "the floral teacup or the plain
    teacup?", a word the KB names nothing with, may well be how the speaker says one of them:
    asking again would claim neither fits, so it is not understood."""
    lang = reader.lexicon.lang
    if reader.refs.unnamed(content_words(lang, fragment)):
        return Outcome(say(lang, "sorry.not_understood"), understood=False)
    unknown = [w for w in content_words(lang, fragment) if w in lang.words.positions]
    if unknown:
        note = say(lang, "request.position_unknown", position=unknown[0])
        return replace(outcome.followed_up(), reply=f"{note} {outcome.reply}")
    return outcome.followed_up()


def _every(earlier: Reader, pending: Parse, first: Outcome, asked: str) -> Outcome | None:
    """ "both" to "Which mug do you mean: the blue one or the red one?": the request for each thing
    the question told apart, in the order the question listed them (None: it asked about no such
    things)."""
    role = first.open_role
    kinds = ROLE_KINDS.get(pending.intent or "", {}).get(role or "")
    if role is None or kinds is None or not first.open_phrase:
        return None
    lang = earlier.lexicon.lang
    matches = resolve(earlier.lexicon, first.open_phrase, kinds).matches
    listed = [asked.find(option) for option in describe_options(lang, earlier.snapshot, matches)]
    order = sorted(range(len(matches)), key=lambda i: (listed[i] < 0, listed[i]))
    return _several(earlier, [earlier.act(pending, {role: tuple(tokens(matches[i].id))}) for i in order])


def _each(earlier: Reader, pending: Parse, first: Outcome, fragment: Words) -> Outcome | None:
    """ "the yellow one and the black one" to "Which torch do you mean...?": the request for each
    thing named, in the order said (None: the parts do not each name one other thing)."""
    lang, role = earlier.lexicon.lang, first.open_role
    if role is None:
        return None
    parts: list[list[str]] = [[]]
    for w in fragment:
        if w not in lang.followups.joining:
            parts[-1].append(w)
        elif parts[-1]:
            parts.append([])
    each = [earlier.act(pending, {role: _merged(lang, tuple(part), first)}) for part in parts if part]
    if len({o.roles.get(role) for o in each}) < len(each):
        return None  # one thing named twice, or a part that named nothing
    return _several(earlier, each)


def _several(earlier: Reader, each: list[Outcome]) -> Outcome | None:
    """The requests in turn, said one after the other (None: fewer than two, or one not understood)."""
    if len(each) < 2 or any(o.intent is None for o in each):
        return None
    said = then(earlier.lexicon.lang, [o.reply for o in each])
    return replace(each[0].followed_up(), reply=said, more=tuple(o.followed_up() for o in each[1:]))


def _chosen(earlier: Reader, pending: Parse, first: Outcome, fragment: Words) -> Outcome | None:
    """An answer that picks among the things asked about other than by what they are: several in
    turn ("the yellow one and then the black one"), or by their side ("the left one")."""
    if set(fragment) & earlier.lexicon.lang.followups.joining:
        return _each(earlier, pending, first, fragment)
    return _on_the_side(earlier, pending, first, fragment)


def _on_the_side(earlier: Reader, pending: Parse, first: Outcome, fragment: Words) -> Outcome | None:
    """ "the left one" to "Which cup do you mean...?": the one thing asked about that the KB puts on
    that side of every other (`leftOf`, `rightOf`, as the robot sees them); None when it says not."""
    lang, role = earlier.lexicon.lang, first.open_role
    sides = [lang.words.sides[w] for w in content_words(lang, fragment) if w in lang.words.sides]
    kinds = ROLE_KINDS.get(pending.intent or "", {}).get(role or "")
    side = dict(RELATIONS).get(sides[0]) if len(sides) == 1 else None
    if side is None or role is None or kinds is None or not first.open_phrase:
        return None
    matches = resolve(earlier.lexicon, first.open_phrase, kinds).matches
    placed = [e for e in matches if all((side, o.id) in e.relations for o in matches if o.id != e.id)]
    if len(placed) != 1:
        return None
    outcome = earlier.act(pending, {role: tuple(tokens(placed[0].id))})
    return outcome.followed_up() if outcome.intent is not None else None


#: How many answers the same question may have had before this one ("the left one", asked again).
_ASKED_AGAIN = 2


def _pending(reader: Reader, spoken: list[int], heard: Said) -> tuple[int, Parse] | None:
    """The request the robot's question is about, and where it was said: the person's words before
    the question, or before answers that left the question asked again ("the left one")."""
    lang, history = reader.lexicon.lang, reader.history
    question = history[spoken[-1]].text
    for at in range(len(spoken) - 2, max(-1, len(spoken) - 3 - 2 * _ASKED_AGAIN), -2):
        said = history[spoken[at]]
        if said.role != "user" or not question.endswith(history[spoken[at + 1]].text):
            return None  # the question was not asked again: an older request is no longer pending
        pending = parse(lang, heard.of(said.text), reader.robot_name)
        if pending.act == "command":
            return spoken[at], pending
    return None


def _fragment(lang: Language, p: Parse, heard: Said) -> tuple[Words, Words | None]:
    """The words of the answer ("mine, obviously": whose it is, without the interjection), and what
    a clause after it says of the thing ("..., it's Carla's"), if one does."""
    said = clauses(lang, heard)
    more = description(lang, heard.of(said[1])) if len(said) == 2 else None
    words = heard.of(said[0]).tokens if more is not None else p.words
    owners, interjections = lang.words.owners, lang.followups.interjections
    return tuple(owners.get(w, w) for w in _unapproved(lang, words) if w not in interjections), more


def _unapproved(lang: Language, words: Words) -> Words:
    """The answer without what the speaker thinks of it: "on the till counter's fine" is "on the
    till counter", "the red one is good" "the red one"."""
    if len(words) < 2 or words[-1] not in lang.followups.approving:
        return words
    if words[-2] == "is":
        return words[:-2]
    return (*words[:-2], words[-2].removesuffix("'s")) if words[-2].endswith("'s") else words


def _merged(lang: Language, fragment: Words, first: Outcome) -> Words:
    """The fragment with the pending request's phrase: "the red one" and "the cup" make "the red
    cup"; prepositions stay ("the novel" + "book from the shelf" keeps "book" as the head)."""
    if first.open_phrase:
        phrase = tuple(w for w in first.open_phrase if w not in lang.followups.articles)
        if not set(fragment) & lang.followups.one:
            return (*fragment, *phrase)
        return tuple(x for w in fragment for x in (phrase if w in lang.followups.one else (w,)))
    # (a fragment answering "Where should I put it?" may start with its preposition: "on the shelf")
    for loc in lang.prepositions.longest_first("place"):
        if fragment[: len(loc)] == loc:
            return fragment[len(loc) :]
    return fragment


def reaffirmed(reader: Reader, spoken: list[int], question: Utterance, answer: list[str]) -> Outcome | None:
    """ "yes" to "Do you mean the blue mug on the coffee table?" or to "Shall I take the tablet out
    there?" asked of a request the rules read whole (the robot that asked may be another system, or
    was being sure): that reading, when the question proposes or confirms, names a thing or person
    of it (or proposes to act on "it") and names no other (where they are aside). None when the
    words do not say yes, the request does not read whole, or the question is about something else
    ("Is that everything?", "Is it ok if I do it later?")."""
    lang = reader.lexicon.lang
    nos = frozenset(lang.followups.no.values())  # (the word a "nope" or "nah" is read as)
    said = [w for w in answer if w not in nos]
    if set(answer[:1]) & nos or not accepts(lang, said) or len(spoken) < 2:
        return None
    asked = expanded(lang, question.text.rstrip(" ?"))
    leads = [*lang.followups.offers, *lang.followups.confirms]
    at = next((i + len(c) for i in range(len(asked)) for c in leads if tuple(asked[i : i + len(c)]) == c),
              None)  # fmt: skip
    if at is None:
        return None  # ("Anything else?" "yes": not the request again)
    request = reader.history[spoken[-2]]
    if request.role != "user":
        return None
    reading = reader.within(reader.history[: spoken[-2]]).interpret(request.text)
    if reading.intent is None or reading.clarify or not reading.understood:
        return None
    acted = {v for step in reading.steps() for v in step.roles.values()}
    words = [w.removesuffix("'s") for w in tokens(question.text)]
    named = [m for m in reader.lexicon.mentions(words)
             if not set(words[max(0, m.start - 2) : m.start]) & lang.locative]  # fmt: skip
    if any(not m.entities & acted for m in named):
        return None  # ("Shall I take it to Maya?" of a request for Teodor: not what was read)
    if not named and not _on_it(lang, asked[at:], reader.robot_name):
        return None  # ("Is that everything?" "yes": not the request again)
    steps = [replace(o, confidence=min(o.confidence, proposal.CONFIRMED_CONFIDENCE), more=())
             for o in reading.steps()]  # fmt: skip
    return replace(steps[0], more=tuple(steps[1:]))


def _on_it(lang: Language, proposed: list[str], robot_name: str) -> bool:
    """Whether the words after "Shall I" propose to act on the thing of the request said as "it"
    ("take it out there"; "do it later" proposes no act)."""
    p = parse(lang, " ".join(proposed), robot_name)
    return p.act == "command" and p.slots.get("object", ())[:1] in {(w,) for w in lang.words.pronouns}


def confirmation(earlier: Reader, pending: Parse, first: Outcome, question: Utterance,
                 said: list[str]) -> Outcome | None:  # fmt: skip
    """ "yes" or "no, the other one" to "Do you mean the flat brush?": the thing the robot guessed,
    or the one other thing the pending request's phrase names."""
    lang = earlier.lexicon.lang
    asked = expanded(lang, question.text.rstrip(" ?"))
    lead = next((c for c in lang.followups.confirms if tuple(asked[: len(c)]) == c), None)
    role = first.open_role
    if lead is None or role is None or not first.open_phrase:
        return None
    kinds = ROLE_KINDS.get(pending.intent or "", {}).get(role)
    if kinds is None:
        return None
    candidates = resolve(earlier.lexicon, first.open_phrase, kinds).matches
    guessed = resolve(earlier.lexicon, asked[len(lead) :], kinds).one
    if guessed is None or guessed not in candidates:
        return None
    if said[:1] == ["no"] and set(said) & lang.followups.other:  # "no the other one"
        others = [e for e in candidates if e.id != guessed.id]
        meant = others[0] if len(others) == 1 else None
    elif said[:1] != ["no"] and accepts(lang, said):
        meant = guessed
    else:
        return None
    if meant is None:
        return None
    outcome = earlier.act(pending, {role: tuple(tokens(meant.id))})
    return outcome if outcome.intent is not None else None


def continuation(reader: Reader, p: Parse, heard: Said) -> Outcome | None:
    """ "and the soup goes to table two", "and the soup to table two" after "take the steak to table
    four": the request just made (a bringing) again, for another thing and place. Alone, "X goes to
    Y" says no request."""
    lang = reader.lexicon.lang
    words = tuple(strip_politeness(lang, plain(lang, heard)))
    found = where_it_goes(lang, words)
    to = lang.followups.continued_to
    if found is None and to in words[1:-1]:  # said without its verb
        at = words.index(to)
        found = words[:at], (to,), words[at + 1 :]
    if found is None or found[1] != (to,):
        return None
    asked = [i for i, u in enumerate(reader.history) if u.role == "user"]
    if not asked:
        return None
    pending = parse(lang, heard.of(reader.history[asked[-1]].text), reader.robot_name)
    if pending.act != "command" or pending.intent != I.BRING_OBJECT:
        return None
    thing, _, place = found
    again = Parse("command", I.BRING_OBJECT, {"object": thing, "recipient": place}, words=(*thing, *place),
                  marks={"recipient": (to,)})  # fmt: skip
    outcome = reader.act(again)
    return outcome.followed_up() if outcome.intent is not None else None


#: What an utterance in which the grammar reads no act may be, in the order tried: an answer to the
#: robot's question, a correction of the request just made, the same request for another thing.
FOLLOW_UPS: tuple[Callable[[Reader, Parse, Said], Outcome | None], ...] = (
    follow_up, correction, continuation,
)  # fmt: skip


def said_first(reader: Reader, heard: Said, said: list[str]) -> Outcome | None:
    """ "Oh, not the kitchen, the balcony. I want some fresh air.": an answer or a correction said in
    the first clauses, the later ones saying why (and no request of their own that could be done)."""
    for end in range(len(said) - 1, 0, -1):
        first = heard.of(", ".join(said[:end]))
        p = parse(reader.lexicon.lang, first, reader.robot_name)
        outcome = followed_up(reader, p, first) if p.act == "unknown" else None
        if outcome is not None and outcome.intent is not None:
            return outcome
    return None


def followed_up(reader: Reader, p: Parse, heard: Said) -> Outcome | None:
    """What the first follow-up that reads the utterance made of it (`FOLLOW_UPS`)."""
    for read in FOLLOW_UPS:
        outcome = read(reader, p, heard)
        if outcome is not None:
            return outcome
    return None
