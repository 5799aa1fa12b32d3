"""Speech asked for: "tell Ana that...", "say X to Y", quoted words, "let Tom know...": what to
say, to whom."""

from __future__ import annotations

from lemminflect import getLemma

from dialogue import intents as I
from dialogue.reference.english import Words
from dialogue.understanding.parsed import Parse
from dialogue.understanding.requests.constructions import ConstructionGrammar, Framed
from dialogue.understanding.said import QUOTED
from dialogue.understanding.speech.clauses import finite
from dialogue.understanding.speech.plain import expanded, message, original_text, split_at


def letting_know(said: Framed) -> Parse | None:
    """ "let Tom know that dinner is ready" is "tell Tom that...". """
    if "know" not in said.rest:
        return None
    told = tuple(x for x in said.rest if x != "know")
    return speech(Framed(said.lang, ("tell",), told, said.words, said.original))


def _plural(word: str) -> bool:
    """Whether a noun is a plural ("kids", "children")."""
    lemmas = getLemma(word, "NOUN")
    return bool(lemmas) and lemmas[0] != word


def _clause_start(c: ConstructionGrammar, rest: Words) -> int | None:
    """Where a clause with a subject of its own starts after the person told, if one does: a subject
    pronoun ("tell Noor *it*'s time"), or a noun phrase and its verb ("tell Kasia *her courgettes
    are* ready", "tell Ana *the taxi is* here")."""
    starts = (i for i in range(1, len(rest) - 1) if rest[i] in c.subjects or _subject_phrase(c, rest, i))
    return next(starts, None)


#: At most this many words of a subject before its verb ("the customer for the grey car has...").
_SUBJECT_WORDS = 6


def _subject_phrase(c: ConstructionGrammar, rest: Words, i: int) -> bool:
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
    c = said.lang.derived(ConstructionGrammar)
    verb, rest, original = " ".join(said.verb), said.rest, said.original
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
        elif verb == "ask":  # "ask Ana if she wants tea": a question put to her, when it can be
            return _question_put(said, c, rest) or unknown
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
    found = split_at(rest, [("to",)])
    text_words, recipient = (found[0], found[2]) if found is not None else (rest, ())
    if not text_words:
        return unknown
    return said.command(I.SAY, text=original_text(said.lang, original, text_words), recipient=recipient)


def _said_to(said: Framed, rest: Words) -> Parse:
    """ "(say) to Sandeep that the film starts soon", "(say) to Ana it's time": the person, then the
    message ("that" or a clause of its own starts it)."""
    found = split_at(rest, [("that",)])
    clause = _clause_start(said.lang.derived(ConstructionGrammar), rest)
    if found is not None and (clause is None or len(found[0]) <= clause):
        recipient, text = found[0], found[2]
    elif clause is not None:
        recipient, text = rest[:clause], rest[clause:]
    else:
        return Parse("unknown", words=said.words)
    if not text:
        return said.command(I.SAY, recipient=recipient)
    return said.command(I.SAY, text=message(said.lang, said.original, text), recipient=recipient)


def _question_put(said: Framed, c: ConstructionGrammar, rest: Words) -> Parse | None:
    """ "ask Ollie if he wants a sausage": "do you want a sausage?" said to Ollie; None when the
    question cannot be put to them as "you" ("ask Ana if the taxi is here")."""
    at = next((i for i, w in enumerate(rest) if w in c.asked_whether), None)
    if at is None or at == 0 or len(rest) < at + 4 or rest[at + 1] not in c.asked_of:
        return None
    verb, after = rest[at + 2], rest[at + 3 :]
    if set(after) & c.asked_not_after:
        return None
    if verb in c.asked_as_you:
        question = (*c.asked_as_you[verb], *after)
    else:
        lemmas = getLemma(verb, "VERB")
        if not lemmas or lemmas[0] == verb or verb in c.verbs_of_any:
            return None  # no verb of the third person ("if he wanted"): not put as said
        question = (*c.asked_plain, lemmas[0], *after)
    return said.command(I.SAY, text=" ".join(question) + "?", recipient=rest[:at])
