"""The rules interpreter: a parsed utterance, grounded against the KB lexicon, to a reply and an intent.

Every referent is resolved here to exactly one KB entity (or the speaker for "me"); otherwise the
outcome has no intent and the reply says what is unknown or asks which one was meant. A fragment
answering the robot's last question ("the red one") completes the request found in the history.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Sequence
from dataclasses import replace

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.prompts import FREE_FORM_OBJECT
from dialogue.reference.clarify import question as clarifying_question
from dialogue.reference.grounding import Entity, Kind
from dialogue.reference.lexicon import Lexicon, tokens
from dialogue.reference.resolution import (
    ANYWHERE,
    PERSON,
    POSSESSIVES,
    ROLE_KINDS,
    antecedent,
    content_words,
    is_pronoun,
    resolve,
)  # fmt: skip
from dialogue.rules import answers
from dialogue.rules.commands import LOCATIVE, ME, Parse, Words, parse
from dialogue.rules.compound import Part, alternatives, conjuncts, coordinated, unprefixed
from dialogue.rules.outcome import Outcome, Ref
from dialogue.rules.replies import acknowledgement, vocative
from dialogue.rules.words import COLOURS, INTERJECTIONS, cleaned, word_set

_ONE = frozenset({"one", "ones"})
#: Punctuation, dashes, and (for unpunctuated speech) a polite request starting mid-utterance.
_CLAUSE_BREAK = re.compile(
    r"[.;!?,]+(?:\s+|$)|\s+(?:-|\u2013|\u2014)\s+|\s+(?=(?:could|can|would|will)\s+you\b|please\b)"
    # A trailing clause with a subject of its own: "...the wine cellar she wants to pick a bottle",
    # "...my aspirin it is in one of the drawers", "...my eyeglass you can find it on the table".
    r"|\s+(?=(?:she|he|it|they|you)\s+(?:is|are|was|were|wants|needs|should|might|must|can|could|has|have|just)\b)",
    re.I,
)
#: Spatial or comparative qualifiers the KB does not model (dropped when they block a match).
RELATIONAL = word_set(
    "left right front back behind near nearest closest far farthest big bigger biggest small smaller "
    "smallest large larger largest little other first second third last middle top bottom"
)
_MANY = word_set("and both all every each")
#: An answer naming an owner ("mine", "hers") is the possessive phrase ("my cup").
_POSSESSIVE_OF = {"mine": "my", "yours": "your", "ours": "our", "hers": "her", "theirs": "their"}
#: Words that need no name in the KB to be understood in a phrase.
_ACCOUNTED = RELATIONAL | COLOURS | ME | word_set(
    "it them him her here there over something anything around nearby about"
)


class Interpreter:
    def __init__(
        self, lexicon: Lexicon, speaker: str, history: Sequence[Utterance] = (), robot_name: str = "robot"
    ) -> None:
        self.lexicon = lexicon
        self.snapshot = lexicon.snapshot
        self.speaker = speaker
        self.history = tuple(history)
        self.robot_name = robot_name

    def interpret(self, text: str) -> Outcome:
        text = cleaned(text)
        parts = conjuncts(text)
        if parts:
            combined = self._compound(parts)
            if combined is not None:
                return combined
        return self._single(text)

    def _compound(self, parts: Sequence[Part]) -> Outcome | None:
        """ "go to the kitchen and take the plate": every part read in order, each with the parts
        before it as context for its pronouns ("take the book and put it in the oven")."""
        done: list[Outcome] = []
        cannot: list[str] = []
        for n, part in enumerate(parts):
            context = tuple(Utterance(self.speaker, p.text) for p in parts[:n])
            reader = Interpreter(self.lexicon, self.speaker, (*self.history, *context), self.robot_name)
            if n == 0 and part.verb is None:
                continue  # a preamble ("hey there", "thanks", "the denim jacket"): context for the rest
            outcome = reader._single(part.text)
            if outcome.intent is not None:
                done.append(outcome)
            elif outcome.clarify:
                return outcome  # ask about this part first: nothing is done until it is clear
            elif part.no_intent:
                cannot.append(part.text)
            else:  # a part that fails says why; one not understood makes the whole not understood
                return outcome if outcome.understood else None
        if not done:
            return None
        acks = [done[0].reply] + [f"Then {unprefixed(o.reply)}" for o in done[1:]]
        acks += [f"I can't {c} myself." for c in cannot]
        return replace(done[0], reply=" ".join(acks), more=tuple(done[1:]))

    def _single(self, text: str) -> Outcome:
        p = parse(text, self.robot_name)
        not_understood = Outcome("Sorry, I did not understand that.", understood=False)
        outcome = (self._follow_up(p, text) or not_understood) if p.act == "unknown" else self.act(p)
        ungrounded = p.act == "command" and outcome.intent is None and not outcome.clarify
        failed = not outcome.understood or ungrounded
        return self._clause_by_clause(text, outcome) if failed else outcome

    def _clause_by_clause(self, text: str, whole: Outcome) -> Outcome:
        """ "The denim jacket. Pick it up." or "Felix wants the remote, can you hand it to him?": when
        the whole utterance is not one request, the last clause that is one is read with the clauses
        before it as context for its pronouns."""
        clauses = [c for c in _CLAUSE_BREAK.split(text) if c.strip()]
        if len(clauses) < 2:
            return whole
        question: Outcome | None = None
        for i in range(len(clauses) - 1, -1, -1):
            context = tuple(Utterance(self.speaker, c) for c in clauses[:i])
            reader = Interpreter(self.lexicon, self.speaker, (*self.history, *context), self.robot_name)
            p = parse(clauses[i], self.robot_name)
            if p.act in {"command", "question"}:
                outcome = reader.act(p)
                if outcome.intent is not None:
                    return outcome
                # A complete request in an earlier clause beats asking about an incomplete later one.
                if question is None and (outcome.clarify or (p.act == "question" and outcome.understood)):
                    question = outcome
        return question or whole

    def act(self, p: Parse, overrides: dict[str, Words] | None = None) -> Outcome:
        if p.act == "greeting" and "everyone" in p.slots:  # no single recipient: greet verbally only
            return Outcome("Hello everyone!")
        if p.act == "greeting":
            hello = f"Hello{vocative(self.snapshot, self.speaker)}!"
            return self._intent(I.GREET, {"recipient": self.speaker}, hello)
        if p.act == "negated":
            return Outcome("OK, I won't do that.")
        if p.act == "thanks":
            return Outcome("You're welcome!")
        if p.act == "question":
            return self._answer(p)
        if p.act == "command" and p.intent is not None:
            return self._command(p, overrides or {})
        return Outcome("Sorry, I did not understand that.", understood=False)

    # -- questions -------------------------------------------------------------------------------
    def _answer(self, p: Parse) -> Outcome:
        thing = p.slots.get("thing", ()) or p.slots.get("place", ())
        if p.question in {"where", "can_see", "what_is", "what_on", "whose"} and is_pronoun(thing):
            ref = antecedent(self.lexicon, [u.text for u in self.history], ANYWHERE)
            if ref is not None:
                thing = tuple(tokens(ref.id))
        content = content_words(thing)
        if content and self._half_known(content) and not resolve(self.lexicon, thing, ANYWHERE).matches:
            return Outcome("Sorry, I don't know how to answer that.", understood=False)
        match p.question:
            case "what_see":
                return Outcome(answers.what_do_you_see(self.snapshot, self.speaker))
            case "who_see":
                return Outcome(answers.who_do_you_see(self.snapshot, self.speaker))
            case "where":
                return Outcome(answers.where_is(self.lexicon, thing, self.speaker))
            case "what_on":
                reply, clarify = answers.what_is_on(self.lexicon, thing)
                return Outcome(reply, clarify=clarify)
            case "can_see":
                return Outcome(answers.can_you_see(self.lexicon, thing, self.speaker))
            case "what_is":
                return Outcome(answers.what_is(self.lexicon, thing, self.speaker))
            case "which_see":
                return Outcome(answers.which_do_you_see(self.lexicon, thing))
            case "how_many":
                return Outcome(answers.how_many(self.lexicon, thing))
            case "colour":
                return Outcome(answers.colour_of(self.lexicon, thing, self.speaker))
            case "whose":
                return Outcome(answers.whose(self.lexicon, thing, self.speaker))
            case "name":
                return Outcome(f"My name is {self.robot_name}.")
            case "how_are_you":
                return Outcome("I'm fine, thank you!")
        return Outcome("Sorry, I don't know how to answer that.", understood=False)

    # -- commands --------------------------------------------------------------------------------
    def _command(self, p: Parse, overrides: dict[str, Words]) -> Outcome:
        whole = self._one_command(p, overrides)
        things = coordinated(p.slots.get("object", ())) if "object" not in overrides else []
        if whole.intent is not None or whole.clarify or len(things) < 2:
            return whole
        # "bring me the cereals and the milk": one intent per thing, in order.
        each = [self._one_command(p, {**overrides, "object": t}) for t in things]
        if any(o.intent is None for o in each):
            return next(o for o in each if o.intent is None)
        acks = [each[0].reply] + [f"Then {unprefixed(o.reply)}" for o in each[1:]]
        return replace(each[0], reply=" ".join(acks), more=tuple(each[1:]))

    def _one_command(self, p: Parse, overrides: dict[str, Words]) -> Outcome:
        intent = p.intent or ""
        slots = {**p.slots, **overrides}
        if p.double_object and "rest" in slots:
            slots = self._split_double_object(slots.pop("rest"))
        if intent in {I.BRING_OBJECT, I.PLACE_OBJECT} and "recipient" in slots:
            # "take Maria to the kitchen", "walk Mr Ito back to the car park": guiding, not carrying
            who = tuple(w for w in slots.get("object", ()) if w not in RELATIONAL)
            if self._person_as_object(who) is not None:
                intent, slots = I.GUIDE, {"recipient": who, "goal": slots["recipient"]}
        implicit = not content_words(slots.get("recipient", ()))
        if intent == I.GUIDE and slots.get("goal") == ("there",) and implicit:
            # "Ellen needs the utility room, lead the way": the person just spoken of, else the speaker.
            person = antecedent(self.lexicon, [u.text for u in self.history], PERSON)
            slots["recipient"] = tuple(tokens(person.id)) if person is not None else ("me",)
        roles: dict[str, str] = {}
        refs: dict[str, Ref] = {}
        spec = I.CATALOGUE[intent]
        for role, kinds in ROLE_KINDS.get(intent, {}).items():
            words = slots.get(role, ())
            if not content_words(words) and words not in {("there",), ("over", "there")}:
                if role in spec.required:
                    return self._missing(intent, role, p)
                continue
            words, owner = self._possessive(words, slots) if role == "object" else (words, None)
            ref = self._ground(words, kinds, role, owner)
            if ref.problem is not None:
                return ref.problem
            refs[role] = ref
            roles[role] = self.speaker if ref.speaker else (ref.entity.id if ref.entity else "")
        if p.text is not None:
            roles["object"] = p.text
        elif intent in {I.SAY, I.START_ACTIVITY, I.PERFORM_MOTION, I.PRESENT_CONTENT}:
            return self._missing(intent, "object", p)
        return self._intent(intent, roles, acknowledgement(self.snapshot, self.speaker, intent, roles, refs))

    def _split_double_object(self, rest: Words) -> dict[str, Words]:
        """ "bring Maria the book": the longest leading phrase naming one person is the recipient."""
        for k in range(len(rest) - 1, 0, -1):
            head, tail = rest[:k], rest[k:]
            if not content_words(tail):
                continue
            people = content_words(head)
            named = set(people) <= ME or resolve(self.lexicon, head, PERSON).one is not None
            # "bring him the bottle": a person pronoun the conversation resolves.
            said = set(people) <= {"him", "her", "them"} and self._person_as_object(head) is not None
            if people and (named or said):
                return {"object": tail, "recipient": head}
        return {"object": rest, "recipient": ("me",)}

    def _person_as_object(self, words: Words) -> Entity | None:
        if content_words(words) and set(content_words(words)) <= ME:
            return self.snapshot.get(self.speaker) or Entity(self.speaker, "you", (), (), (), "person", True)
        if content_words(words) and set(content_words(words)) <= {"him", "her", "them"}:
            return antecedent(self.lexicon, [u.text for u in self.history], PERSON)
        if not content_words(words) or is_pronoun(words):
            return None
        return resolve(self.lexicon, words, PERSON).one

    def _possessive(self, words: Words, slots: dict[str, Words]) -> tuple[Words, str | None]:
        """ "my phone", "give Ines her phone": the phrase without the possessive, and whose it is."""
        rest = tuple(w for w in words if w not in POSSESSIVES)
        said = [w for w in words if w in POSSESSIVES]
        if not said or not content_words(rest):
            return words, None
        if said[0] in {"my", "our"}:
            return rest, self.speaker
        if said[0] == "your":
            return rest, self.snapshot.robot
        # "his/her/their": the person the same request names, else the one the conversation last named.
        other = slots.get("recipient", ())
        person = None if set(other) & ME else self._person_as_object(other)
        person = person or antecedent(self.lexicon, [u.text for u in self.history], PERSON)
        return rest, person.id if person is not None else None

    def _ground(self, words: Words, kinds: frozenset[Kind], role: str, owner: str | None = None) -> Ref:
        content = content_words(words)
        if "person" in kinds and content and set(content) <= ME | {"here"}:
            return Ref(speaker=True)
        bare = {w for w in words if w not in {"the", "over", "please"}}
        if is_pronoun(words) or (bare and bare <= {"him", "her", "there"}):
            history = [u.text for u in self.history]
            found = antecedent(self.lexicon, history, kinds, place=bare == {"there"})
            if found is None:
                return Ref(
                    problem=Outcome(
                        f'What do you mean by "{" ".join(content or sorted(bare))}"?',  # "there" is glue
                        clarify=True,
                        open_role=role,
                        open_phrase=words,
                    )
                )
            return Ref(entity=found)
        res = resolve(self.lexicon, words, kinds, owner=owner)
        if res.ambiguous and any(e.id == self.speaker for e in res.matches):
            # A speaker says "me", not "the person in the living room": a description is someone else.
            res = replace(res, matches=tuple(e for e in res.matches if e.id != self.speaker))
        if res.one is not None:
            return Ref(entity=res.one)
        if res.ambiguous:
            q = clarifying_question(self.snapshot, res.matches)
            return Ref(problem=Outcome(q, clarify=True, open_role=role, open_phrase=words))
        loose = tuple(w for w in words if w not in RELATIONAL)
        if loose != tuple(words) and content_words(loose):
            # "the cup on the left": spatial relations are not in the KB; if the rest of the phrase
            # names one thing, that is it, else ask which one.
            res = resolve(self.lexicon, loose, kinds, owner=owner)
            if res.one is not None:
                return Ref(entity=res.one)
            if res.ambiguous:
                q = clarifying_question(self.snapshot, res.matches)
                return Ref(problem=Outcome(q, clarify=True, open_role=role, open_phrase=loose))
        if set(words) & _MANY:  # "the cup and the apple", "both cups": more than one intent can carry
            return Ref(problem=Outcome("Sorry, one thing at a time, please.", understood=False))
        for alternative in alternatives(words):  # "an apple or an orange": either will do
            ref = self._ground(alternative, kinds, role, owner)
            if ref.entity is not None or ref.speaker:
                return ref
        if self._half_known(content):
            # Names the KB knows among words it does not ("mr ito back", "the trousers out"): the
            # phrase was not understood, which is not the same as "there is no such thing".
            return Ref(problem=Outcome("Sorry, I did not understand that.", understood=False))
        return Ref(problem=Outcome(self._unknown(content, kinds)))

    def _half_known(self, content: Sequence[str]) -> bool:
        """Whether some words of a phrase are names of the KB and others are words it does not know."""
        unknown = [w for w in content if not self.lexicon.knows(w) and w not in _ACCOUNTED]
        return 0 < len(unknown) < len(content)

    def _unknown(self, content: Sequence[str], kinds: Collection[Kind]) -> str:
        phrase = " ".join(content)
        if kinds == PERSON:
            return f"Sorry, I don't know anyone called {phrase.title()}."
        if "zone" in kinds and "person" not in kinds:
            return f"Sorry, I don't know where the {phrase} is."
        if "person" in kinds and resolve(self.lexicon, content, ANYWHERE).matches == ():
            return f"Sorry, I don't know who or where {phrase.title()} is."
        return f"Sorry, I don't see any {phrase}."

    def _missing(self, intent: str, role: str, p: Parse) -> Outcome:
        asks = {
            (I.PLACE_OBJECT, "recipient"): "Where should I put it?",
            (I.MOVE_TO, "goal"): "Where should I go?",
            (I.GUIDE, "goal"): "Where should I take you?",
            (I.SAY, "object"): "What should I say?",
            (I.START_ACTIVITY, "object"): "Which activity should I start?",
        }
        what = {"object": "what", "recipient": "to whom", "goal": "where"}.get(role, "what")
        q = asks.get((intent, role), f"Sorry, {what} exactly?")
        return Outcome(q, clarify=True, open_role=role)

    def _intent(self, intent: str, roles: dict[str, str], reply: str, confidence: float = 0.9) -> Outcome:
        return Outcome(reply, intent, roles, confidence)

    # -- follow-ups to the robot's last question ------------------------------------------------
    def _follow_up(self, p: Parse, text: str) -> Outcome | None:
        """ "the red one" after "Which cup do you mean...?" re-reads the pending request with it."""
        # "mine, obviously": whose it is, without the interjection.
        fragment = tuple(_POSSESSIVE_OF.get(w, w) for w in p.words if w not in INTERJECTIONS)
        # The robot's question must be the latest utterance (system notes aside), right after a request.
        spoken = [i for i, u in enumerate(self.history) if u.role != "system"]
        if not fragment or len(spoken) < 2:
            return None
        i, before = spoken[-1], spoken[-2]
        question, request = self.history[i], self.history[before]
        if question.role != "assistant" or not question.text.rstrip().endswith("?") or request.role != "user":
            return None
        earlier = Interpreter(self.lexicon, self.speaker, self.history[:before], self.robot_name)
        pending = parse(request.text, self.robot_name)
        if pending.act != "command":
            return None
        first = earlier.act(pending)
        if first.open_role is None:
            return None
        if first.open_phrase:
            # Prepositions stay: "the novel" + "book from the shelf" keeps "book" as the head.
            phrase = tuple(w for w in first.open_phrase if w not in {"the", "a", "an"})
            merged = tuple(x for w in fragment for x in (phrase if w in _ONE else (w,)))
            if not set(fragment) & _ONE:
                merged = (*fragment, *phrase)
        else:
            merged = tuple(fragment)
            for loc in LOCATIVE:
                if merged[: len(loc.split())] == tuple(loc.split()):
                    merged = merged[len(loc.split()) :]
                    break
        role = first.open_role
        if role == "object" and pending.intent in FREE_FORM_OBJECT:  # "What should I say?" "Dinner is ready"
            pending = replace(pending, text=text.strip().rstrip(".!?").strip() or None)
        outcome = earlier.act(pending, {role: merged})
        if outcome.intent is None and not outcome.clarify:
            return None
        return Outcome(
            outcome.reply,
            outcome.intent,
            outcome.roles,
            0.8,
            clarify=outcome.clarify,
            open_role=outcome.open_role,
            open_phrase=outcome.open_phrase,
        )
