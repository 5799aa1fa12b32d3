"""Noun phrases of a request grounded in the KB: one entity, the speaker, or why not (unknown, ambiguous,
not understood); possessives ("my phone", "give Ines her phone") and double objects ("bring Maria the
book") read against the people the KB knows and the conversation.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import replace

from lemminflect import getAllLemmas

from dialogue.history import Utterance
from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.english import Words, tokens
from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.lexicon import Lexicon, singular
from dialogue.reference.resolution import (
    ANYWHERE,
    PERSON,
    THING,
    ZONE,
    antecedent,
    content_words,
    is_pronoun,
    pronoun_kinds,
    resolve,
    said_phrase,
)
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome, Ref
from dialogue.understanding.replies import say
from dialogue.understanding.requests.compound import alternatives
from dialogue.understanding.speech.clauses import described
from dialogue.understanding.speech.sounds import slipped as heard_as


def relational(lang: Language) -> frozenset[str]:
    """Spatial or comparative qualifiers the KB does not model (dropped when they block a match)."""
    return lang.words.positions | lang.requests.referents.relational


class _Words:
    """The language's words a role's phrase is grounded with (made once per language)."""

    def __init__(self, lang: Language) -> None:
        closed, said = lang.words, lang.requests.referents
        self.relational = relational(lang)
        #: Words that need no name in the KB to be understood in a phrase.
        self.accounted = self.relational | closed.colours | closed.me | said.accounted
        #: Words that address someone without naming them ("take it to sir"): whom the KB calls
        #: otherwise.
        self.address = frozenset(w for p in lang.speech.tags for w in p) - closed.possessives
        self.every = said.every
        #: Words that say how much of a thing, not which ("get me some", "bring me a couple").
        self.some = said.some
        self.determiners = closed.determiners
        self.function_words = closed.any_function_word
        self.many = closed.many
        self.me = closed.me
        self.modifier_start = lang.modifier_start
        self.parts = closed.parts
        self.personal = closed.personal
        self.possessives = closed.possessives
        self.support = lang.support
        self.np_start = closed.np_start
        self.purpose = lang.requests.purpose


class Referents:
    def __init__(self, lexicon: Lexicon, speaker: str, history: Sequence[Utterance] = ()) -> None:
        self.lexicon = lexicon
        self.lang = lexicon.lang
        self.said = lexicon.lang.derived(_Words)
        self.snapshot = lexicon.snapshot
        self.speaker = speaker
        self.history = tuple(history)

    def split_double_object(self, rest: Words) -> dict[str, Words]:
        """ "bring Maria the book": the longest leading phrase naming one person is the recipient."""
        for k in range(len(rest) - 1, 0, -1):
            head, tail = rest[:k], rest[k:]
            if not content_words(self.lang, tail) or self._whose(head[-1]):
                continue  # "fetch Marco's jacket": whose the thing is, not to whom
            people = content_words(self.lang, head)
            named = set(people) <= self.said.me or resolve(self.lexicon, head, PERSON).one is not None
            # "bring him the bottle": a person pronoun the conversation resolves.
            said = set(people) <= {"him", "her", "them"} and self.person_as_object(head) is not None
            # "bring her the muffin": "her" before a determiner is no possessive, whoever she is
            said = said or (set(head) <= self.said.personal and tail[0] in self.said.determiners)
            if people and (named or said):
                return {"object": tail, "recipient": head}
        return {"object": rest, "recipient": ("me",)}

    def _whose(self, word: str) -> bool:
        """Whether the word is a person's possessive: "Marco's", or "marcos" as a recogniser writes it."""
        if word.endswith("'s"):
            return True
        if not word.endswith("s") or len(word) < 4:
            return False
        named = self.lexicon.names_at([word[:-1]], 0)
        people = [e for n in named if (e := self.snapshot.get(n.entity)) is not None and e.kind == "person"]
        # (a person whose name it is is no possessive: "Ines" is not Ine's)
        return bool(people) and not any(word in tokens(label) for e in people for label in e.labels)

    def every(self, words: Words) -> list[Words]:
        """ "all the plates", "both cups": each thing the phrase names, as its id ([] when the phrase
        is not quantified, or names nothing)."""
        if not set(words) & self.said.every or set(words) & {"and", "or"}:
            return []
        rest = tuple(w for w in words if w not in self.said.every and w != "of")
        return [tuple(tokens(e.id)) for e in resolve(self.lexicon, rest, THING).matches]

    def named_in(self, phrases: Sequence[Words]) -> Entity | None:
        """The one person the phrases name, as a name or a possessive ("Ravi's stapler"), if one."""
        people: set[str] = set()
        for words in phrases:
            bare = [w[:-2] if w.endswith("'s") and len(w) > 2 else w for w in words]
            for mention in self.lexicon.mentions(bare):
                found = [e for e in mention.entities if (x := self.snapshot.get(e)) and x.kind == "person"]
                people.update(found if len(found) == 1 else ())
        return self.snapshot.get(next(iter(people))) if len(people) == 1 else None

    def a_place(self, words: Words) -> bool:
        """Whether the phrase names one place (a zone of the KB) and no thing ("the lifts")."""
        if not content_words(self.lang, words) or is_pronoun(self.lang, words):
            return False
        if resolve(self.lexicon, words, THING).matches:
            return False
        return resolve(self.lexicon, words, ZONE).one is not None

    def a_person(self, words: Words) -> bool:
        """Whether the phrase is someone: a person's name, a person pronoun or the speaker."""
        content = set(content_words(self.lang, words))
        return bool(content) and (content <= self.said.personal | self.said.me or self.named_person(words))

    def named_person(self, words: Words) -> bool:
        """Whether the phrase names one person of the KB (not a pronoun, not the speaker's "me")."""
        content = content_words(self.lang, words)
        if not content or is_pronoun(self.lang, words) or set(content) & self.said.me:
            return False
        return resolve(self.lexicon, words, PERSON).one is not None

    def person_as_object(self, words: Words) -> Entity | None:
        content = content_words(self.lang, words)
        if content and set(content) <= self.said.me:
            return self.snapshot.get(self.speaker) or Entity(self.speaker, "you", (), (), (), "person", True)
        if content and set(content) <= {"him", "her", "them"}:
            # "them" is people only when no thing was spoken of ("take them to her": the specs)
            if not set(content) <= self.said.personal and antecedent(self.lexicon, self.history, THING):
                return None
            return antecedent(self.lexicon, self.history, PERSON, speaker=self.speaker)
        if not content or is_pronoun(self.lang, words):
            return None
        return resolve(self.lexicon, words, PERSON).one

    def some_of(self, words: Words) -> Words:
        """ "some", "one", "a couple" said for a thing: the thing the conversation just named ("I
        need biscuits, can you get me some"), as its id; the words as they are when none was."""
        if not set(words) <= self.said.some | {"a", "of", "them"} or not set(words) & self.said.some:
            return words
        found = antecedent(self.lexicon, self.history, THING, speaker=self.speaker)
        return tuple(tokens(found.id)) if found is not None else words

    def possessive(self, words: Words, slots: dict[str, Words]) -> tuple[Words, str | None]:
        """ "my phone", "give Ines her phone": the phrase without the possessive, and whose it is."""
        rest = tuple(w for w in words if w not in self.said.possessives)
        said = [w for w in words if w in self.said.possessives]
        if not said or not content_words(self.lang, rest):
            return words, None
        if said[0] in {"my", "our"}:
            return rest, self.speaker
        if said[0] == "your":
            return rest, self.snapshot.robot
        # "his/her/their": the person the same request names, else the one the conversation last named.
        other = slots.get("recipient", ())
        person = None if set(other) & self.said.me else self.person_as_object(other)
        person = person or antecedent(self.lexicon, self.history, PERSON, speaker=self.speaker)
        return rest, person.id if person is not None else None

    def ground(  # noqa: C901
        self,
        words: Words,
        kinds: frozenset[Kind],
        role: str,
        owner: str | None = None,
        said: Sequence[Words] = (),
    ) -> Ref:
        """The entity a role's phrase names; `said` are the request's other phrases, where a person
        pronoun finds the one person they name ("take Ravi's scarf to him")."""
        bare_words = [w for w in words if w not in self.said.determiners]
        something = bare_words[:1] in (["something"], ["anything"])
        wanted = self.said.purpose(tuple(bare_words[1:])) if something else None
        if wanted is not None:  # "something to eat": food; "something to cut this with": a cutting tool
            words = wanted
        words = _apposed(self.lang, _not_the_other(self.lang, _placed_pronoun(self.lang, words)))
        content = content_words(self.lang, words)
        if "person" in kinds and content and set(content) <= self.said.me | {"here"}:
            return Ref(speaker=True)
        bare = {w for w in words if w not in {"the", "over", "please"}}
        if is_pronoun(self.lang, words) or (bare and bare <= {"him", "her", "there"}):
            kinds = pronoun_kinds(self.lang, words, kinds)
            if not kinds:  # "go and get him": a person where the request wants a thing
                return Ref(problem=self._not_understood())
            found = self.named_in(said) if kinds == PERSON else None
            found = found or antecedent(self.lexicon, self.history, kinds, place=bare == {"there"},
                                        speaker=self.speaker)  # fmt: skip
            if found is None and self._unknown_just_said():
                # "my case is by the door, bring it over": "it" is what the KB has no name for
                return Ref(problem=self._not_understood())
            if found is None:
                return Ref(
                    problem=Outcome(
                        # ("there" is glue)
                        say(self.lang, "sorry.what_meant", phrase=" ".join(content or sorted(bare))),
                        clarify=True,
                        open_role=role,
                        open_phrase=words,
                    )
                )
            return Ref(entity=found)
        addressed = "person" in kinds and content and set(content) <= self.said.address
        if addressed and not self.named_person(words):
            # "take my calculator to sir": someone the KB knows by name, which one a model may know
            return Ref(problem=self._not_understood())
        res = resolve(self.lexicon, words, kinds, owner=owner)
        if res.ambiguous and any(e.id == self.speaker for e in res.matches):
            # A speaker says "me", not "the person in the living room": a description is someone else.
            res = replace(res, matches=tuple(e for e in res.matches if e.id != self.speaker))
        if res.one is not None:
            return Ref(entity=res.one)
        slipped = heard_as(self.lexicon, words, kinds, owner)
        if slipped is not None:
            return Ref(entity=slipped, guessed=True)
        loose = tuple(w for w in words if w not in self.said.relational)
        if res.ambiguous and loose != tuple(words) and content_words(self.lang, loose):
            # "the box of plasters back": a position word kept the name from matching
            one = resolve(self.lexicon, loose, kinds, owner=owner).one
            if one is not None:
                return Ref(entity=one)
        if res.ambiguous:
            q = clarifying_question(self.lang, self.snapshot, res.matches, self._noun(words, res.matches))
            return Ref(problem=Outcome(q, clarify=True, open_role=role, open_phrase=words))
        if loose != tuple(words) and content_words(self.lang, loose):
            # "the cup on the left": spatial relations are not in the KB; if the rest of the phrase
            # names one thing, that is it, else ask which one.
            res = resolve(self.lexicon, loose, kinds, owner=owner)
            if res.one is not None:
                return Ref(entity=res.one)
            if res.ambiguous:
                q = clarifying_question(self.lang, self.snapshot, res.matches, self._noun(loose, res.matches))
                return Ref(problem=Outcome(q, clarify=True, open_role=role, open_phrase=loose))
        titled = self._titled(words, kinds)
        if titled is not None:
            return Ref(entity=titled)
        place = self._put_by(words, kinds, role, owner)
        if place is not None:
            return place
        # "the cup and the apple", "both cups": more than one intent can carry
        if set(words) & self.said.many:
            return Ref(problem=Outcome(say(self.lang, "sorry.one_at_a_time"), understood=False))
        for alternative in alternatives(self.lang, words):  # "an apple or an orange": either will do
            ref = self.ground(alternative, kinds, role, owner)
            if ref.entity is not None or ref.speaker:
                return ref
        if self.half_known(content) or set(content) <= self.said.relational | self.said.parts:
            # "to the front", "on the left": whereabouts of nothing named, which a model may know.
            # Names the KB knows among words it does not ("mr ito back", "the trousers out"): the
            # phrase was not understood, which is not the same as "there is no such thing".
            return Ref(problem=self._not_understood())
        other = resolve(self.lexicon, words, ANYWHERE - kinds).matches if ANYWHERE - kinds else ()
        if other or ("person" in kinds and words[:1] and words[0] in self.said.possessives):
            # "go and get Ben from the garden": a person where a thing is wanted, no intent the rules
            # have, or a place ("pop plot 12 down"): not "I don't see any plot 12"; "my son":
            # someone the KB knows only by how the speaker is related to them
            return Ref(problem=self._not_understood())
        reply = self.unknown(content, kinds, words)
        if {"one", "ones"} & set(words):
            # "the ones on the bench": which ones the conversation means, not that no bench is here
            return Ref(problem=self._not_understood())
        if self.strange(content) or (kinds == PERSON and not set(words) & self.said.determiners):
            # "I don't see any bk": only true of a kind the rules know; of a word they do not, it is
            # a doubt, for a model to read ("bk" is "back" in chat); so is a name no one has here, a
            # recogniser's spelling of one a model may see in the situation ("chevonne": Siobhan)
            return Ref(problem=Outcome(reply, understood=False))
        return Ref(problem=Outcome(reply))

    def _not_understood(self) -> Outcome:
        return Outcome(say(self.lang, "sorry.not_understood"), understood=False)

    def _titled(self, words: Words, kinds: frozenset[Kind]) -> Entity | None:
        """ "my reserved book murder on the orient express (on the reservations shelf under jeff)": a
        thing said by the whole of a label of three words or more with a preposition in it (a title)
        at the head of the phrase, with words before it the KB cannot check and modifiers after it:
        that thing, when one thing has the label."""
        for start in range(len(words)):
            if words[start] in self.said.modifier_start:
                return None  # (a title inside a modifier names where, not what)
            titles = {n.entity: n for n in self.lexicon.names_at(words, start)
                      if n.source == "label" and len(n.words) > 2
                      and set(n.words[1:-1]) & self.said.modifier_start}  # fmt: skip
            if titles:
                name = next(iter(titles.values()))
                after = words[start + len(name.words) :]
                entity = self.snapshot.get(name.entity) if len(titles) == 1 else None
                modified = not after or after[0] in self.said.modifier_start
                if entity is None or entity.kind not in kinds or not modified:
                    return None
                return entity
        return None

    def _noun(self, words: Words, candidates: Sequence[Entity]) -> str | None:
        """The noun said for all the candidates ("a drink"), if the phrase ends its core with one."""
        core: list[str] = []
        for w in words:
            if w in self.said.modifier_start and core:
                break
            core.append(w)
        content = content_words(self.lang, core)
        if not content:
            return None
        noun = singular(content[-1])
        named = {n.entity for n in self.lexicon.names_at([noun], 0) if len(n.words) == 1}
        return noun if all(c.id in named for c in candidates) else None

    def _put_by(self, words: Words, kinds: frozenset[Kind], role: str, owner: str | None) -> Ref | None:
        """ "put the book next to the cup on the shelf" when the cup is not on the shelf: the last
        place is where to put it (the verb's), the first only says whereabouts on it."""
        if role != "recipient" or "zone" not in kinds or "person" in kinds:
            return None
        at = max((i for i, w in enumerate(words) if w in self.said.support and i > 0), default=None)
        if at is None or not content_words(self.lang, words[at + 1 :]):
            return None
        ref = self.ground(words[at + 1 :], kinds, role, owner)
        return ref if ref.entity is not None else None

    def _unknown_just_said(self) -> bool:
        """Whether the words just said before this request (the same utterance's earlier clause)
        name something with a noun the KB does not know."""
        last = self.history[-1] if self.history else None
        if last is None or last.role != "user":
            return False
        return any(
            not self.lexicon.knows(w) and "NOUN" in getAllLemmas(w)
            for w in tokens(last.text)
            if w.isalpha() and w not in self.said.function_words | self.said.accounted
        )

    def strange(self, content: Sequence[str]) -> list[str]:
        """The words of a phrase that nothing accounts for: no name or qualifier of the KB, no word of
        English (lemminflect's lexicon), no number or function word ("bk", "thingummy")."""
        return [w for w in content if not self.lexicon.knows(w) and w not in self.said.accounted
                and w not in self.said.function_words and not getAllLemmas(w.removesuffix("'s"))]  # fmt: skip

    def half_known(self, content: Sequence[str]) -> bool:
        """Whether some words of a phrase are names of the KB and others are words it does not know."""
        unknown = [w for w in content if not self.lexicon.knows(w) and w not in self.said.accounted]
        return 0 < len(unknown) < len(content)

    def unknown(self, content: Sequence[str], kinds: Collection[Kind], words: Sequence[str] = ()) -> str:
        phrase = " ".join(content)
        if kinds == PERSON:
            return say(self.lang, "sorry.no_one_called", name=phrase.title())
        if "zone" in kinds and "person" not in kinds:
            return say(self.lang, "sorry.no_place", phrase=phrase)
        if "person" in kinds and resolve(self.lexicon, content, ANYWHERE).matches == ():
            return say(self.lang, "sorry.no_one_or_place", name=phrase.title())
        return say(self.lang, "sorry.none_seen", phrase=said_phrase(self.lang, words) or phrase)


def _apposed(lang: Language, words: Words) -> Words:
    """ "my mug the yellow one": a second phrase of "one" says which the first is ("my yellow mug")."""
    if "one" not in words and "ones" not in words:
        return words
    for j in range(1, len(words)):
        np_start = lang.words.np_start
        if words[j] in np_start and words[j - 1] not in np_start and words[j - 1] not in lang.modifier_start:
            if "one" in words[j:] or "ones" in words[j:]:
                return described(lang, words[:j], words[j:])
            return words
    return words


def _placed_pronoun(lang: Language, words: Words) -> Words:
    """ "it off the shelf", "them from the table": the pronoun; where it is only says where to take it
    from (the thing is the one the conversation named)."""
    if len(words) > 2 and words[0] in {"it", "them"} and words[1] in lang.support:
        return words[:1]
    return words


def _not_the_other(lang: Language, words: Words) -> Words:
    """ "the box of gloves not the plasters": the thing meant, without the one it is not."""
    at = next((i for i in range(1, len(words)) if words[i] == "not" and words[i + 1 : i + 2]), None)
    return words if at is None or not content_words(lang, words[:at]) else words[:at]
