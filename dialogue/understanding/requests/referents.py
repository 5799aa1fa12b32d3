"""What a request's noun phrases say of the KB's entities, before and while they are grounded
(dialogue.understanding.requests.ground): possessives ("my phone", "give Ines her phone"), double
objects ("bring Maria the book"), people, places, quantities, read against the people the KB knows
and the conversation."""

from __future__ import annotations

from collections.abc import Sequence

from dialogue.history import Utterance
from dialogue.reference.antecedent import antecedent
from dialogue.reference.english import Words, tokens
from dialogue.reference.grounding import Entity
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.naming import phrase, singular
from dialogue.reference.resolution import (
    PERSON,
    THING,
    ZONE,
    content_words,
    is_pronoun,
    resolve,
)
from dialogue.understanding.language import Language
from dialogue.understanding.lemmas import lemmas_of
from dialogue.understanding.requests.kin import kin_word


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
        self.owner = said.owner
        self.beneficiary = said.beneficiary
        #: Words that say how much of a thing, not which ("get me some", "bring me a couple").
        self.some = said.some
        self.some_glue = said.some_glue
        self.person_objects = said.person_objects
        self.pronoun_like = said.pronoun_like
        self.pronoun_glue = said.pronoun_glue
        self.one = closed.one
        self.coordinators = closed.coordinators
        self.speaker_possessives = frozenset(closed.speaker_possessives)
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
            named = named or kin_word(self.lang, head) is not None  # "bring my wife her phone"
            # "bring him the bottle": a person pronoun the conversation resolves.
            said = set(people) <= self.said.person_objects and self.person_as_object(head) is not None
            # "bring her the muffin": "her" before a determiner is no possessive, whoever she is
            said = said or (set(head) <= self.said.personal and tail[0] in self.said.determiners)
            if people and (named or said):
                return {"object": tail, "recipient": head}
        # "give daddy my drawing": words before the thing's phrase are whom, even when no one here is
        # called so; never the speaker by default
        # ("bring granny her specs": "her" before a noun starts the thing's phrase too)
        closed = self.said
        at = next((i for i in range(1, len(rest)) if rest[i] in closed.np_start or (
            rest[i] in closed.possessives and rest[i + 1 :] and rest[i + 1] not in closed.determiners)), 0)
        head = rest[:at]
        plain = not any(self._whose(w) or w in self.said.modifier_start for w in head)  # not "Omar's hat off"
        if head and plain and rest[0] not in self.said.np_start and content_words(self.lang, head):
            return {"object": rest[len(head) :], "recipient": head}
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
        if not set(words) & self.said.every or set(words) & self.said.coordinators:
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
        zone = resolve(self.lexicon, words, ZONE).one
        return zone is not None and self.headed(words, zone)

    def headed(self, words: Words, entity: Entity) -> bool:
        """Whether the phrase's last word is the head of the entity's name: "the lifts" of the lifts,
        not "the tool" of the "tool shed", whose name only holds the word."""
        content, name = content_words(self.lang, words), phrase(entity.name)
        return bool(content) and bool(name) and singular(name[-1]) == singular(content[-1])

    def a_person(self, words: Words) -> bool:
        """Whether the phrase is someone: a person's name, a person pronoun or the speaker."""
        content = set(content_words(self.lang, words))
        return bool(content) and (content <= self.said.personal | self.said.me or self.named_person(words))

    def someone_else(self, words: Words) -> bool:
        """Whether the phrase is a person other than the speaker: named, or "him" / "her"."""
        content = set(content_words(self.lang, words))
        return (bool(content) and content <= self.said.personal) or self.named_person(words)

    def named_person(self, words: Words) -> bool:
        """Whether the phrase names one person of the KB (not a pronoun, not the speaker's "me")."""
        content = content_words(self.lang, words)
        if not content or is_pronoun(self.lang, words) or set(content) & self.said.me:
            return False
        return resolve(self.lexicon, words, PERSON).one is not None

    def named_across(
        self, slots: dict[str, Words], marks: dict[str, Words]
    ) -> tuple[dict[str, Words], dict[str, Words]]:
        """ "take the key card for room 309 to Mrs Okafor": a thing whose name the grammar cut at a
        role's preposition is the thing called so, and the role is what follows its name (said
        after a preposition of its own), when the words up to there are exactly one name."""
        thing = slots.get("object", ())
        for role, words in slots.items():
            mark = marks.get(role)
            if role == "object" or mark is None or not thing:
                continue
            for end in range(len(words), 0, -1):
                named = (*thing, *mark, *words[:end])
                bare = named[1:] if named[0] in self.said.np_start else named
                found = self.lexicon.mentions(bare)
                if len(found) != 1 or (found[0].start, found[0].end) != (0, len(bare)):
                    continue
                if len(found[0].entities) != 1:
                    break
                rest, out = words[end:], {**slots, "object": named}
                kept = {r: m for r, m in marks.items() if r != role}
                if rest and rest[0] in self.said.function_words and rest[1:]:  # "... to Mrs Okafor"
                    out[role], kept[role] = rest[1:], (rest[0],)
                else:  # (the role said only as part of the name: read as the grammar cut it)
                    break
                return out, kept
        return slots, marks

    def an_owner(self, words: Words) -> bool:
        """Whether the phrase is whom a thing belongs to ("its owner"): a person, whoever it is."""
        content = content_words(self.lang, words)
        return bool(content) and set(content) <= self.said.owner

    def person_as_object(self, words: Words) -> Entity | None:
        content = content_words(self.lang, words)
        if content and set(content) <= self.said.me:
            return self.snapshot.get(self.speaker) or Entity(self.speaker, "you", (), (), (), "person", True)
        if content and set(content) <= self.said.person_objects:
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
        if not set(words) <= self.said.some | self.said.some_glue or not set(words) & self.said.some:
            return words
        found = antecedent(self.lexicon, self.history, THING, speaker=self.speaker)
        return tuple(tokens(found.id)) if found is not None else words

    def possessive(self, words: Words, slots: dict[str, Words]) -> tuple[Words, str | None]:
        """ "my phone", "give Ines her phone": the phrase without the possessive, and whose it is."""
        rest = tuple(w for w in words if w not in self.said.possessives)
        said = [w for w in words if w in self.said.possessives]
        if not said or not content_words(self.lang, rest):
            return words, None
        if said[0] in self.said.speaker_possessives:
            return rest, self.speaker
        if said[0] == "your":
            return rest, self.snapshot.robot
        # "his/her/their": the person the same request names, else the one the conversation last named.
        other = slots.get("recipient", ())
        person = None if set(other) & self.said.me else self.person_as_object(other)
        person = person or antecedent(self.lexicon, self.history, PERSON, speaker=self.speaker)
        return rest, person.id if person is not None else None

    def strange(self, content: Sequence[str]) -> list[str]:
        """The words of a phrase that nothing accounts for: no name or qualifier of the KB, no word of
        English (lemminflect's lexicon), no number or function word ("bk", "thingummy")."""
        return [w for w in content if not self.lexicon.knows(w) and w not in self.said.accounted
                and w not in self.said.function_words and not lemmas_of(w.removesuffix("'s"))]  # fmt: skip

    def unnamed(self, content: Sequence[str]) -> list[str]:
        """The words of a phrase no name or qualifier of the KB accounts for, English or not ("bunny"
        of a toy rabbit, "bagget" heard for a baguette): the rules cannot tell a thing that is not
        here from a thing called otherwise, or misheard."""
        return [w for w in content if not self.lexicon.knows(w) and w not in self.said.accounted
                and w not in self.said.function_words]  # fmt: skip

    def half_known(self, content: Sequence[str]) -> bool:
        """Whether some words of a phrase are names of the KB and others are words it does not know."""
        unknown = [w for w in content if not self.lexicon.knows(w) and w not in self.said.accounted]
        return 0 < len(unknown) < len(content)
