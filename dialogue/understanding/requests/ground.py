"""A role's phrase grounded in the KB: one entity, the speaker, or the outcome that says why not.

Grounding is an ordered tuple of small steps (`STEPS`, in the manner of CoreNLP's coreference
sieves): each reads the phrase and either decides (a `Ref`) or leaves it to the next. What no step
decides is a thing, a place or a person not here (`_none_here`).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Sequence

from dialogue.reference.antecedent import antecedent, pronoun_kinds
from dialogue.reference.english import Words, tokens
from dialogue.reference.grounding import Kind
from dialogue.reference.lexicon import singular
from dialogue.reference.resolution import (
    ANYWHERE,
    PERSON,
    PLACE,
    THING,
    content_words,
    is_pronoun,
    resolve,
    said_phrase,
)
from dialogue.reference.snapshot import fixed
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.outcome import Outcome, Ref
from dialogue.understanding.replies import say, the
from dialogue.understanding.requests.compound import alternatives
from dialogue.understanding.requests.kin import kin_word, relatives, said_so
from dialogue.understanding.requests.phrase import Phrase, prepared
from dialogue.understanding.requests.referents import Referents
from dialogue.understanding.speech.sounds import clipped as said_short
from dialogue.understanding.speech.sounds import slipped as heard_as


def ground(
    refs: Referents,
    words: Words,
    kinds: frozenset[Kind],
    role: str,
    owner: str | None = None,
    said: Sequence[Words] = (),
) -> Ref:
    """The entity a role's phrase names; `said` are the request's other phrases, where a person
    pronoun finds the one person they name ("take Ravi's scarf to him")."""
    phrase = Phrase(refs, prepared(refs, words), kinds, role, owner, said)
    for step in STEPS:
        ref = step(phrase)
        if ref is not None:
            return _carried(phrase, ref)
    return _none_here(phrase)


def _carried(p: Phrase, ref: Ref) -> Ref:
    """A request's object is picked up or carried: furniture, or what the KB says cannot be moved,
    is answered with why not ("grab the sofa"), never an intent the robot cannot carry out."""
    entity = ref.entity
    if p.role != "object" or entity is None or not fixed(entity):
        return ref
    name = the(p.refs.lang, p.refs.snapshot, entity)
    return Ref(problem=Outcome(say(p.refs.lang, "sorry.fixed", thing=name)))


# -- the steps, in order -------------------------------------------------------------------------
def _the_speaker(p: Phrase) -> Ref | None:
    """ "me", "here" where a person is wanted: the speaker."""
    if "person" in p.kinds and p.content and set(p.content) <= p.refs.said.me | {"here"}:
        return Ref(speaker=True)
    return None


def _family(p: Phrase) -> Ref | None:
    """ "my wife", "Dad": the one person the KB relates to the speaker so; asked when it names no
    one or several ("Who is your wife?"), never guessed."""
    refs = p.refs
    word = kin_word(refs.lang, p.words) if "person" in p.kinds else None
    if word is None or p.resolved.matches:
        return None  # (someone the KB calls "grandma" is called so)
    found = relatives(refs.lang, refs.snapshot, refs.speaker, word)
    one = refs.snapshot.get(found[0]) if len(found) == 1 else None
    if one is not None and said_so(refs.lang, one, word):
        return Ref(entity=one)
    asked = say(refs.lang, "request.who_kin", kin=word)
    return Ref(problem=Outcome(asked, clarify=True, open_role=p.role))


def _someone_there(p: Phrase) -> Ref | None:
    """ "bring it to her in the bedroom", "to the bakehouse for Tomás": a recipient said with where
    they are is the person, not the place the phrase would otherwise name."""
    refs, words = p.refs, p.words
    if p.role != "recipient" or "person" not in p.kinds or len(words) < 3:
        return None
    for i in range(1, len(words) - 1):
        if words[i] in refs.said.support:  # "her in the bedroom"
            who, where = words[:i], words[i + 1 :]
        elif words[i] in refs.said.beneficiary:  # "the bakehouse for Tomás"
            where, who = words[:i], words[i + 1 :]
        else:
            continue
        if resolve(refs.lexicon, where, frozenset({"zone"})).one is None:
            continue
        ref = ground(refs, who, PERSON, p.role, p.owner, p.said)
        if ref.speaker or (ref.entity is not None and ref.entity.kind == "person"):
            return ref
    return None


def _pronoun(p: Phrase) -> Ref | None:
    """ "it", "him", "there": the one the request or the conversation names, else which is meant."""
    refs = p.refs
    bare = {w for w in p.words if w not in refs.said.pronoun_glue}
    if not (is_pronoun(refs.lang, p.words) or (bare and bare <= refs.said.pronoun_like)):
        return None
    kinds = pronoun_kinds(refs.lang, p.words, p.kinds)
    if not kinds:  # "go and get him": a person where the request wants a thing
        return p.not_understood()
    found = refs.named_in(p.said) if kinds == PERSON else None
    # "there", and a pronoun where a thing is put ("and put the book next to it" after "I've put
    # the tin on the coffee table"): the place last spoken of first, not the thing put there
    there = bare == {"there"} or (p.role == "recipient" and p.kinds == PLACE)
    found = found or antecedent(refs.lexicon, refs.history, kinds, place=there, speaker=refs.speaker)
    if found is None and _unknown_just_said(refs):
        # "my case is by the door, bring it over": "it" is what the KB has no name for
        return p.not_understood()
    if found is None:
        # ("there" is glue)
        meant = say(refs.lang, "sorry.what_meant", phrase=" ".join(p.content or sorted(bare)))
        return Ref(problem=Outcome(meant, clarify=True, open_role=p.role, open_phrase=p.words))
    return Ref(entity=found)


def _addressed(p: Phrase) -> Ref | None:
    """ "take my calculator to sir": someone the KB knows by name, which one a model may know."""
    addressed = "person" in p.kinds and p.content and set(p.content) <= p.refs.said.address
    return p.not_understood() if addressed and not p.refs.named_person(p.words) else None


def _owner(p: Phrase) -> Ref | None:
    """ "give it to its owner": whom the KB says the one thing of the request belongs to."""
    refs = p.refs
    if "person" not in p.kinds or not p.content or not set(p.content) <= refs.said.owner:
        return None
    things = {ref.entity.id: ref.entity for words in p.said
              if (ref := ground(refs, words, THING, "object")).entity is not None}  # fmt: skip
    if len(things) != 1:
        return p.not_understood()
    thing = next(iter(things.values()))
    owner = refs.snapshot.get(thing.owner) if thing.owner else None
    if owner is None:
        name = the(refs.lang, refs.snapshot, thing)
        return Ref(problem=Outcome(say(refs.lang, "answers.owner_unknown", name=name)))
    return Ref(entity=owner)


def _named(p: Phrase) -> Ref | None:
    """The one entity the phrase names."""
    one = p.resolved.one
    return Ref(entity=one) if one is not None else None


def _slipped(p: Phrase) -> Ref | None:
    """ "bay mine": the one name a slip of the ear or the keys is of, a guess."""
    slipped = heard_as(p.refs.lexicon, p.words, p.kinds, p.owner)
    return Ref(entity=slipped, guessed=True) if slipped is not None else None


def _clipped(p: Phrase) -> Ref | None:
    """ "the mic": the one name a word said short is the start of, a guess."""
    if p.resolved.matches:
        return None
    found = said_short(p.refs.lexicon, p.words, p.kinds, p.owner)
    return Ref(entity=found, guessed=True) if found is not None else None


def _qualified(p: Phrase) -> Ref | None:
    """ "the box of plasters back": a position word kept the name from matching."""
    if not (p.resolved.ambiguous and p.loosened):
        return None
    one = resolve(p.refs.lexicon, p.loose, p.kinds, owner=p.owner).one
    return Ref(entity=one) if one is not None else None


def _just_named(p: Phrase) -> Ref | None:
    """ "give me the book" just after the robot said "a green mug and a crime novel": of the several
    things the phrase names, the one the robot's last words named."""
    history = p.refs.history
    if not p.resolved.ambiguous or not history or history[-1].role == "user":
        return None
    named = {e for m in p.refs.lexicon.mentions(tokens(history[-1].text)) for e in m.entities}
    meant = [e for e in p.resolved.matches if e.id in named]
    return Ref(entity=meant[0]) if len(meant) == 1 else None


def _ambiguous(p: Phrase) -> Ref | None:
    """Several things the phrase names: which one."""
    return p.which(p.resolved.matches, p.words) if p.resolved.ambiguous else None


def _placed(p: Phrase) -> Ref | None:
    """ "the cup on the left": spatial relations are not in the KB; if the rest of the phrase names
    one thing, that is it, else which one."""
    if not p.loosened:
        return None
    res = resolve(p.refs.lexicon, p.loose, p.kinds, owner=p.owner)
    if res.one is not None:
        return Ref(entity=res.one)
    return p.which(res.matches, p.loose) if res.ambiguous else None


def _titled(p: Phrase) -> Ref | None:
    """ "my reserved book murder on the orient express (on the reservations shelf under jeff)": a
    thing said by the whole of a label of three words or more with a preposition in it (a title)
    at the head of the phrase, with words before it the KB cannot check and modifiers after it:
    that thing, when one thing has the label."""
    refs, words = p.refs, p.words
    for start in range(len(words)):
        if words[start] in refs.said.modifier_start:
            return None  # (a title inside a modifier names where, not what)
        titles = {n.entity: n for n in refs.lexicon.names_at(words, start)
                  if n.source == "label" and len(n.words) > 2
                  and set(n.words[1:-1]) & refs.said.modifier_start}  # fmt: skip
        if titles:
            name = next(iter(titles.values()))
            after = words[start + len(name.words) :]
            entity = refs.snapshot.get(name.entity) if len(titles) == 1 else None
            modified = not after or after[0] in refs.said.modifier_start
            if entity is None or entity.kind not in p.kinds or not modified:
                return None
            return Ref(entity=entity)
    return None


def _put_by(p: Phrase) -> Ref | None:
    """ "put the book next to the cup on the shelf" when the cup is not on the shelf: the last
    place is where to put it (the verb's), the first only says whereabouts on it; "the round table
    out on the terrace", where it is, is the round table."""
    if p.role != "recipient" or "zone" not in p.kinds or "person" in p.kinds:
        return None
    words = p.words
    at = max((i for i, w in enumerate(words) if w in p.refs.said.support and i > 0), default=None)
    if at is None or not content_words(p.refs.lang, words[at + 1 :]):
        return None
    ref = ground(p.refs, words[at + 1 :], p.kinds, p.role, p.owner)
    if ref.entity is None:
        return None
    # "the round table out on the terrace": the first place, said with where it is, when it is there
    head_words = words[:at]
    while head_words and head_words[-1] in p.refs.lang.words.function_words:  # ("... table out on")
        head_words = head_words[:-1]
    head = resolve(p.refs.lexicon, head_words, p.kinds - {"zone"}, owner=p.owner).one
    return Ref(entity=head) if head is not None and ref.entity.id in {head.support, head.zone} else ref


def _many(p: Phrase) -> Ref | None:
    """ "the cup and the apple", "both cups": more than one intent can carry."""
    if set(p.words) & p.refs.said.many:
        return Ref(problem=Outcome(say(p.refs.lang, "sorry.one_at_a_time"), understood=False))
    return None


def _either(p: Phrase) -> Ref | None:
    """ "an apple or an orange": either will do."""
    for alternative in alternatives(p.refs.lang, p.words):
        ref = ground(p.refs, alternative, p.kinds, p.role, p.owner)
        if ref.entity is not None or ref.speaker:
            return ref
    return None


def _whereabouts(p: Phrase) -> Ref | None:
    """ "to the front", "on the left": whereabouts of nothing named, which a model may know. Names
    the KB knows among words it does not ("mr ito back", "the trousers out"): the phrase was not
    understood, which is not the same as "there is no such thing"."""
    said = p.refs.said
    if p.refs.half_known(p.content) or set(p.content) <= said.relational | said.parts:
        return p.not_understood()
    return None


def _another_kind(p: Phrase) -> Ref | None:
    """ "go and get Ben from the garden": a person where a thing is wanted, no intent the rules have,
    or a place ("pop plot 12 down"): not "I don't see any plot 12"; "my son": someone the KB knows
    only by how the speaker is related to them."""
    others = ANYWHERE - p.kinds
    other = resolve(p.refs.lexicon, p.words, others).matches if others else ()
    # ("bring me the tool": the "tool shed" is not what is meant, and no tool is seen)
    other = tuple(e for e in other if e.kind != "zone" or p.refs.headed(p.words, e))
    if other or ("person" in p.kinds and p.words[:1] and p.words[0] in p.refs.said.possessives):
        return p.not_understood()
    return None


def _ones(p: Phrase) -> Ref | None:
    """ "the ones on the bench": which ones the conversation means, not that no bench is here."""
    return p.not_understood() if p.refs.said.one & set(p.words) else None


#: The steps of grounding, in the order they are tried.
STEPS: tuple[Callable[[Phrase], Ref | None], ...] = (
    _the_speaker, _family, _someone_there, _pronoun, _addressed, _owner, _named, _slipped, _clipped,
    _qualified, _just_named, _ambiguous, _placed, _titled, _put_by, _many, _either, _whereabouts,
    _another_kind, _ones,
)  # fmt: skip


def _none_here(p: Phrase) -> Ref:
    """What no step grounded: nothing such is here. "I don't see any mug" is only true of a kind the
    KB names; of a word it does not, English or not, it is a doubt, for a model to read ("bk" is
    "back" in chat, "bunny" may be the toy rabbit, "the remove" the remote misheard); so is a name
    no one has here, a recogniser's spelling of one a model may see in the situation ("chevonne":
    Siobhan, "armed": Ahmed)."""
    refs = p.refs
    reply = unknown(refs, p.content, p.kinds, p.words)
    # ("the bread on the bread shelf": "bread" only says which shelf, no loaf or baguette is called so)
    if refs.unnamed(p.content) or _head_names_nothing(p) or (
        p.kinds == PERSON and not set(p.words) & refs.said.determiners
    ):
        return Ref(problem=Outcome(reply, understood=False))
    return Ref(problem=Outcome(reply))


def _head_names_nothing(p: Phrase) -> bool:
    """Whether the phrase's head noun, known to the KB only inside other names ("bread" of the "bread
    shelf"), names nothing by itself: what the speaker calls so may be a thing called otherwise."""
    if "thing" not in p.kinds or p.kinds == PERSON:
        return False
    core: list[str] = []
    for w in p.words:
        if w in p.refs.said.modifier_start and core:
            break
        core.append(w)
    content = content_words(p.refs.lang, core)
    if not content:
        return False
    return not any(len(n.words) == 1 for n in p.refs.lexicon.names_at([singular(content[-1])], 0))


def unknown(
    refs: Referents, content: Sequence[str], kinds: Collection[Kind], words: Sequence[str] = ()
) -> str:
    """The reply that says nothing the phrase names is here."""
    lang, phrase = refs.lang, " ".join(content)
    if kinds == PERSON:
        return say(lang, "sorry.no_one_called", name=phrase.title())
    if "zone" in kinds and "person" not in kinds:
        return say(lang, "sorry.no_place", phrase=phrase)
    if "person" in kinds and resolve(refs.lexicon, content, ANYWHERE).matches == ():
        return say(lang, "sorry.no_one_or_place", name=phrase.title())
    return say(lang, "sorry.none_seen", phrase=said_phrase(lang, words) or phrase)


def _unknown_just_said(refs: Referents) -> bool:
    """Whether the words just said before this request (the same utterance's earlier clause) name
    something with a noun the KB does not know."""
    last = refs.history[-1] if refs.history else None
    if last is None or last.role != "user":
        return False
    return any(
        not refs.lexicon.knows(w) and "NOUN" in lemmas_of(w)
        for w in tokens(last.text)
        if w.isalpha() and w not in refs.said.function_words | refs.said.accounted
    )


