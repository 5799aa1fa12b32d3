"""Reading an utterance's words: its act (a request, a question, a greeting, thanks, a refusal) and,
for a request, the verb frame it fits (dialogue.understanding.requests.frames) with each role's phrase (D11).

Only words are looked at: which entity a phrase names is decided later against the KB
(dialogue.understanding.interpret), so no noun is written here.
"""

from __future__ import annotations

from dataclasses import replace

from dialogue.reference.english import Words
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Act, Parse
from dialogue.understanding.questions.grammar import question as _question
from dialogue.understanding.requests.adjuncts import adjuncts_of
from dialogue.understanding.requests.constructions import Framed
from dialogue.understanding.requests.frames import Frame, Row, verb_index
from dialogue.understanding.requests.kin import kin_word
from dialogue.understanding.requests.motions import as_motion
from dialogue.understanding.requests.needs import chore_needed
from dialogue.understanding.requests.timing import conditional, later, negation, when
from dialogue.understanding.requests.vocabulary import Grammar
from dialogue.understanding.said import Said, Text
from dialogue.understanding.speech.plain import strip_politeness
from dialogue.understanding.speech.repair import normalise, strip_vocative, verb_lemma

__all__ = ["Parse", "Words", "parse"]



def parse(lang: Language, said: Text, robot_name: str = "") -> Parse:
    """What the grammar reads in the words: their act and, for a request, its frame's roles."""
    g = lang.derived(Grammar)
    heard = Said.read(lang, said)
    words = strip_vocative(lang, strip_politeness(lang, normalise(lang, heard), robot_name), robot_name)
    if not words:
        return Parse("unknown", words=())
    words[0] = verb_lemma(lang, words[0])  # "(would you mind) picking up the cup"
    if words[0] == "no" and len(words) > 1 and words[1] not in g.after_no:
        words = strip_politeness(lang, words[1:], robot_name)
    if len(words) > 1 and words[0] in g.halts and negation(g, words[1:]):  # "stop, don't go"
        words = words[1:]
    if words and negation(g, words):
        return Parse("negated", words=tuple(words))
    if g.again.of(words):  # "do the same with the blue one"
        return Parse("unknown", words=tuple(words))
    if conditional(g, words) or later(lang, words):  # "if Declan comes by, give him the menu"
        return Parse("conditional", words=tuple(words))
    if not words:
        return Parse("unknown", words=())
    if words[0] in g.thanks or words == ["cheers"]:
        # "thanks, now put it on the shelf": the thanks is a preamble to the request
        full = len(g.thank_you) if g.thank_you and tuple(words[: len(g.thank_you)]) == g.thank_you else 1
        tail = strip_politeness(lang, words[full:], robot_name)
        # "thanks, bye": the leave-taking is what is answered
        return _talk(g, tail, robot_name) or _request(lang, heard, tail) or _aside("thanks", words, tail)
    if tuple(words) in g.social and words[:1] != ["how"]:
        return Parse("greeting", words=tuple(words))
    talk = _talk(g, words, robot_name)
    if talk is not None:
        return talk
    greeting = None if _welcoming(g, words) else g.greetings.first(words)
    if greeting is not None:
        rest = _after_greeting(lang, words[len(greeting) :], robot_name)
        again = next((a for a in g.greetings.of(rest) if len(rest) > len(a)), ())
        again = () if _welcoming(g, rest) else again  # ("hey Tiago, welcome Mr Dubois")
        rest = _after_greeting(lang, rest[len(again) :], robot_name) if again else rest
        if tuple(rest) in g.social:
            return Parse("greeting", words=tuple(words))
        # "Good morning Maria" is still a greeting; "hi, grab the cup" is a request; "hello
        # robot, what's your name" a greeting and a question.
        after = _request(lang, heard, rest)
        if after is not None and after.act == "question" and greeting not in g.attention:
            return replace(after, greeted=True)
        return after or _aside("greeting", words, rest)
    return _question(lang, words) or command(lang, heard, words)


def _welcoming(g: Grammar, words: list[str]) -> bool:
    """ "welcome Lucia" asks the robot to greet her; "welcome back" is a greeting."""
    return words[:1] == ["welcome"] and len(words) > 1 and words[1] not in g.welcome_back


def _after_greeting(lang: Language, words: list[str], robot_name: str) -> list[str]:
    """What follows a greeting, its politeness and the name it calls ("yo robot. yo. stop": a call
    for attention said again is one too)."""
    return strip_vocative(lang, strip_politeness(lang, words, robot_name), robot_name)


def _talk(g: Grammar, words: list[str], robot_name: str) -> Parse | None:
    """ "bye", "what can you do?", "tell me a joke"; "goodbye robot", "bye Robbie": said to the robot."""
    called = words[:-1] if len(words) > 1 and words[-1] in {"robot", robot_name.lower()} else words
    for act, phrases in g.talk:
        if tuple(called) in phrases:
            return Parse(act, words=tuple(words))
    return None


#: At most this many words after a greeting or thanks are part of it ("good morning Mr Ito").
_ASIDE = 3


def _aside(act: Act, words: list[str], rest: list[str]) -> Parse:
    """A greeting or thanks, unless more follows it than a name: then what follows was not
    understood ("hey robot the red case is mine can you..."), and nor is the whole."""
    return Parse(act, words=tuple(words)) if len(rest) <= _ASIDE else Parse("unknown", words=tuple(words))


def _request(lang: Language, heard: Said, words: list[str]) -> Parse | None:
    """What follows a greeting or thanks, if it is a question or command."""
    if not words:
        return None
    after = _question(lang, words) or command(lang, heard, words)
    return after if after.act != "unknown" else None


def command(lang: Language, original: Said, words: list[str]) -> Parse:
    """The request the words make: the first construction or verb frame that fits them."""
    g = lang.derived(Grammar)
    w = _joined(g, words)
    chore = chore_needed(lang, w)
    if chore is not None:  # "the parcel needs taking to Lars": the taking, if a frame reads it
        asked = command(lang, original, list(chore))
        if asked.act == "command":
            return asked
    said = Framed(lang, (), w, w, original)
    for construction in g.constructions:
        found = construction(said)
        if found is not None:
            return found
    if w:
        w = (verb_lemma(lang, w[0]), *w[1:])
    for verb, row in verb_index(lang).get(w[0], ()) if w else ():
        if tuple(w[: len(verb)]) != verb:
            continue
        # what to say is said as it was ("out of paper"), the roles of a frame read joined
        rest = tuple(words[len(verb) :]) if row.frame.special is not None else w[len(verb) :]
        found = _fit(row, Framed(lang, verb, rest, w, original))
        if found is not None:
            return as_motion(lang, found)
    return Parse("unknown", words=w)


def _joined(g: Grammar, words: list[str]) -> Words:
    """ "next to" as one word ("beside"), so that its "to" is never taken for a recipient's ("out
    of the way" stays: an adjunct, no place)."""
    out: list[str] = []
    for i, word in enumerate(words):
        way = word == "of" and words[i + 1 : i + 3][-1:] == ["way"]
        if out and (out[-1], word) in g.joined and len(out) > 1 and not way:
            out[-1] = g.joined[(out[-1], word)]
        else:
            out.append(word)
    return tuple(out)


def _np_next(lang: Language, rest: Words) -> bool:
    """Whether a noun phrase starts after the first word ("carry me *the* box")."""
    return len(rest) > 1 and rest[1] in lang.words.np_start


def _fit(row: Row, said: Framed) -> Parse | None:
    """The row's reading of what follows the verb, or None when the row does not fit it."""
    frame = row.frame
    if frame.special is not None or frame.intent is None or frame.serial:
        return _unframed(row, said)
    if frame.whole and said.rest:
        return None
    g = said.lang.derived(Grammar)
    rest, adjuncts = adjuncts_of(g, said.rest, row)
    if when(g, adjuncts):  # "say hi to her when she comes in": not now
        return Parse("conditional", words=said.words)
    direct, slots, marks = _segments(g, rest, row)
    if direct:
        direct = _which_one_back(direct, slots, marks, row)
    if frame.here is not None and not (frame.dative and direct[:1] and direct[0] in g.me):
        direct = _here_or_there(g, frame, frame.here, direct, slots)
    if "extra" in slots:  # what a role the intent does not ground says is an adjunct ("for the van")
        adjuncts = (*adjuncts, (" ".join(marks.pop("extra")), *slots.pop("extra")))
    direct = _without_particles(g, direct, row)
    if direct[-1:] and direct[-1] in g.results:  # "get the room ready": no intent of the robot's
        return Parse("unknown", words=said.words)
    if not direct and not slots and set(adjuncts) & g.away:
        return None  # "get out of my way": where not to be is all it says (no thing to get)
    if not direct and frame.direct is not None:
        direct = _second_phrase(g, slots)  # "bring to Ana the tray"
    direct, adjuncts = _handed_me(g, frame, direct, slots, marks, adjuncts)
    if frame.dative is not None and "recipient" not in slots and direct:
        dative = _dative(g, frame, said, direct, slots, adjuncts)
        if isinstance(dative, Parse):
            return dative
        direct = dative
    return _roles(frame, said, direct, slots, marks, adjuncts)


def _unframed(row: Row, said: Framed) -> Parse | None:
    """A row whose frame reads no roles: a function of its own, a verb no intent says, or a verb
    before another ("go get the cup")."""
    frame, rest = row.frame, said.rest
    if frame.special is not None:
        return frame.special(said)
    if frame.intent is None and not frame.serial:  # a verb no intent says ("hand out the sheets")
        only = frame.only
        if only is not None and not (rest[:1] and rest[0] in only and not _np_next(said.lang, rest)):
            return None  # "carry me" has no intent, "carry the box", "carry me the box" other frames'
        return Parse("unknown", words=said.words)
    # "go get the cup", "come say hello to Ana"
    lang = said.lang
    serial = rest and verb_lemma(lang, rest[0]) in verb_index(lang)
    return command(lang, said.original, list(rest)) if serial else None


def _here_or_there(g: Grammar, frame: Frame, here: str, direct: Words, slots: dict[str, Words]) -> Words:
    """The role `here`, which a bare "here" or "there" fills ("leave it over there", "come here",
    "lead the way"; dropped when the place is also named: "lead the way to the lobby"), or
    "somewhere" does; the direct words without it."""
    # ("fetch me that lamp over there": there is where the lamp is)
    # ("wait for me there": what for says no place, the pointing word after it does)
    aside = "extra" if not direct and "extra" in slots else None
    words = slots[aside] if aside is not None else direct
    pointed = next((p for p in g.pointing if words[-len(p[0]) :] == p[0]), None)
    there = pointed is not None and pointed[1] == ("there",)
    if pointed is not None and not (frame.there_only and not there) and not (frame.here_only and there):
        if aside is None:
            direct = direct[: -len(pointed[0])]
        else:
            slots[aside] = words[: -len(pointed[0])]
        slots.setdefault(here, pointed[1])
    at = next((i for i, w in enumerate(direct) if i and w in g.somewhere), None)
    # ("put it somewhere safe": where is asked)
    if at is not None and here not in slots and not frame.here_only:
        direct, slots[here] = direct[:at], direct[at:]
    return direct


def _handed_me(
    g: Grammar, frame: Frame, direct: Words, slots: dict[str, Words], marks: dict[str, Words],
    adjuncts: tuple[Words, ...],
) -> tuple[Words, tuple[Words, ...]]:  # fmt: skip
    """ "bring me the keys to the red car", "pass me the drill for Marcus": the speaker is the
    recipient, what follows "to" or "for" part of the thing or whom it is for."""
    if frame.dative is None or not (direct[:1] and direct[0] in g.me):
        return direct, adjuncts
    if marks.get("recipient") == ("to",):
        # "bring me the keys to the red car": the keys of the car, brought to the speaker
        direct = (*direct[1:], "to", *slots.pop("recipient"))
        slots["recipient"] = ("me",)
        del marks["recipient"]
    elif marks.get("recipient") == ("for",):
        # "pass me the drill for Marcus", "get me a cloth for the spill": the speaker is handed it,
        # whoever or whatever it is for
        adjuncts = (*adjuncts, ("for", *slots.pop("recipient")))
        slots["recipient"], direct = ("me",), direct[1:]
        del marks["recipient"]
    return direct, adjuncts


def _dative(
    g: Grammar, frame: Frame, said: Framed, direct: Words, slots: dict[str, Words],
    adjuncts: tuple[Words, ...],
) -> Parse | Words:  # fmt: skip
    """ "get me a cup", "give Ines her phone": the recipient said first; the direct words after it,
    or a double object the interpreter splits."""
    # "get Ines her phone": someone, then a noun phrase of its own
    # ("take my husband his phone": the speaker's kin are someone too)
    someone = _someone(g, direct[0]) or kin_word(said.lang, direct[:2]) is not None
    before = frame.dative == "before" and someone and _own_phrase_after(g, direct)
    if direct[0] in g.me:  # "get me a cup"
        slots["recipient"], direct = ("me",), direct[1:]
    elif frame.dative == "any" or before:  # "give Ines her phone": the interpreter splits it
        return Parse("command", frame.intent, {"rest": direct}, words=said.words, double_object=True,
                     adjuncts=adjuncts)  # fmt: skip
    return direct


def _roles(
    frame: Frame, said: Framed, direct: Words, slots: dict[str, Words], marks: dict[str, Words],
    adjuncts: tuple[Words, ...],
) -> Parse | None:  # fmt: skip
    """The request with its roles, or None when the frame's roles are not what was said."""
    if direct and frame.direct is None:
        return None
    if direct and frame.direct is not None:
        slots[frame.direct] = direct
    if frame.only is not None and not set(slots.get(frame.direct or "", ("",))) <= frame.only:
        return None
    if any(role not in slots for role in frame.requires):
        return None
    implicit = frozenset(r for r in frame.defaults if r not in slots)
    slots = {**{r: frame.defaults[r] for r in implicit}, **slots}
    text = frame.text(said.lang, said.verb, said.rest) if frame.text is not None else None
    return Parse("command", frame.intent, slots, text=text, words=said.words, adjuncts=adjuncts,
                 implicit=implicit, marks=marks)  # fmt: skip


def _someone(g: Grammar, word: str) -> bool:
    """Whether a word may start the phrase of a person ("him", "Ines"), not of a thing ("all", "the")
    nor a person's thing ("Noor's scarf")."""
    if word.endswith("'s"):
        return False
    return word in g.personal or word == "them" or word not in g.function_words | g.determiners | g.many


def _own_phrase_after(g: Grammar, direct: Words) -> bool:
    """Whether a noun phrase of its own starts within the next words after the first ("Ines *her*
    phone", "Mr Ito *the* menu"), not after a preposition ("Noor's scarf off *the* chair")."""
    starts = range(1, min(4, len(direct)))
    return any(direct[i] in g.own_phrase and direct[i - 1] not in g.modifier_start for i in starts)


def _segments(g: Grammar, rest: Words, row: Row) -> tuple[Words, dict[str, Words], dict[str, Words]]:
    """The words before any of the row's prepositions (the direct role's), and each role's phrase:
    from its preposition to the next role's (a role's preposition said again stays in its phrase:
    "put the cup on the tray on the table"), and the preposition of each."""
    direct: list[str] = []
    slots: dict[str, list[str]] = {}
    marks: dict[str, Words] = {}
    current = direct
    i = 0
    while i < len(rest):
        marker = next((m for m in row.slots if rest[i : i + len(m[0])] == m[0] and m[1] not in slots), None)
        said = marker[0] if marker is not None else ()
        particle = bool(said) and (said[0] in g.goal_particles or said in {(w,) for w in row.particles})
        if particle and not _phrase_at(g, rest, i + 1):
            marker = None  # "go down to the cellar", "put it over by the door": a particle
        if marker is not None and g.purpose(rest[i : i + 2]) is None:  # "something to eat" is no recipient
            current = slots[marker[1]] = []
            marks[marker[1]] = marker[0]
            i += len(marker[0])
            continue
        current.append(rest[i])
        i += 1
    # "take the calculator to": a role cut short is still said (asked for), never dropped
    cut = {r for r, words in slots.items()
           if not words and " ".join(marks[r]) in g.cut_short and current is words}  # fmt: skip
    return tuple(direct), {role: tuple(words) for role, words in slots.items() if words or role in cut}, marks




def _which_one_back(direct: Words, slots: dict[str, Words], marks: dict[str, Words], row: Row) -> Words:
    """ "put the goggles on the front bench back on the shelf": a place said before "back" and the
    role's preposition again says which thing (the goggles on the front bench), the one after it
    where the thing goes. The direct phrase with its modifier; the role's phrase is cut to the
    place after "back"."""
    for preposition, role in row.slots:
        words = slots.get(role, ())
        for i in range(1, len(words) - len(preposition)):
            if words[i] == "back" and words[i + 1 : i + 1 + len(preposition)] == preposition:
                slots[role] = words[i + 1 + len(preposition) :]
                first, marks[role] = marks[role], preposition
                return (*direct, *first, *words[:i])
    return direct


def _phrase_at(g: Grammar, words: Words, i: int) -> bool:
    """Whether a noun phrase starts at i: a determiner, or a word that is no function word ("plot
    12", "Ana's desk")."""
    return i < len(words) and (words[i] in g.np_start or words[i] not in g.function_words)


def _second_phrase(g: Grammar, slots: dict[str, Words]) -> Words:
    """When nothing follows the verb directly, a second noun phrase after a role's own ("to Ana the
    tray", "to Fenna her keys") is the direct one; it is taken out of that role's phrase."""
    for role, words in slots.items():
        for i in range(1, len(words)):
            starts = words[i] in g.np_start or (words[i] == "her" and i + 1 < len(words))
            if starts and words[i - 1] not in g.np_start:
                slots[role] = words[:i]
                return words[i:]
    return ()


def _without_particles(g: Grammar, words: Words, row: Row) -> Words:
    """Particles next to the verb, at the end, or before a preposition ("pick the cup up from the
    table"), never inside a phrase ("the back door")."""
    if not row.particles:
        return words
    out = list(words)
    while out and out[0] in row.particles:
        out.pop(0)
    while out and out[-1] in row.particles:
        out.pop()
    return tuple(w for i, w in enumerate(out) if w not in row.particles or not _before_preposition(g, out, i))


def _before_preposition(g: Grammar, words: list[str], i: int) -> bool:
    return i + 1 < len(words) and words[i + 1] in g.modifier_start
