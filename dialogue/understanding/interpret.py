"""The rules interpreter: a parsed utterance, grounded against the KB lexicon, to a reply and an intent.

Every referent is resolved here to exactly one KB entity (or the speaker for "me"); otherwise the
outcome has no intent and the reply says what is unknown or asks which one was meant. A fragment
answering the robot's last question ("the red one") completes the request found in the history.

The stages, in order: the speech forms (letters joined, slips corrected, false starts cleaned), the
request said to someone else, the terse request, the parts of a compound request, then each part's
act (`ACTS`) or, with no act, its follow-up (`FOLLOW_UPS`), and the clauses one by one when the
whole is not one request.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.reference.antecedent import antecedent
from dialogue.reference.english import Words, tokens
from dialogue.reference.grounding import Entity
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import PERSON, PLACE, ROLE_KINDS, content_words, resolve
from dialogue.understanding.followups.accepting import accepts
from dialogue.understanding.followups.correction import adds_one_more, correction, opens_correction
from dialogue.understanding.followups.proposal import proposed
from dialogue.understanding.followups.request import follow_up, followed_up, said_first
from dialogue.understanding.outcome import Outcome, Ref
from dialogue.understanding.parsed import Parse
from dialogue.understanding.questions import situation
from dialogue.understanding.replies import acknowledgement, hello, say, then, whose_it_is
from dialogue.understanding.requests.abilities import asks_ability
from dialogue.understanding.requests.addressed import to_someone_else
from dialogue.understanding.requests.carrying import carried_onto
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.requests.compound import adds_on, conjuncts, coordinated, two_named
from dialogue.understanding.requests.ground import ground
from dialogue.understanding.requests.owners import none_yours, whose
from dialogue.understanding.requests.referents import Referents, relational
from dialogue.understanding.requests.sequence import compound, wished
from dialogue.understanding.requests.skills import unskilled
from dialogue.understanding.requests.staying import left_as_is
from dialogue.understanding.requests.terse import terse, unasked_thing
from dialogue.understanding.requests.vocabulary import Grammar
from dialogue.understanding.said import Said, Text
from dialogue.understanding.speech.clauses import clauses, described, description
from dialogue.understanding.speech.letters import joined
from dialogue.understanding.speech.plain import expanded
from dialogue.understanding.speech.repair import cleaned, restarted
from dialogue.understanding.speech.spelling import corrected
from dialogue.understanding.talk import TALK

#: How sure the rules are of a turn in which they corrected a slip ("plase", "thremos").
SPELT_CONFIDENCE = 0.7
#: The question that asks for a role not said (`replies.toml` [request]), by intent and role, and
#: by role alone.
_ASKED = {
    (I.PLACE_OBJECT, "recipient"): "request.where_put", (I.MOVE_TO, "goal"): "request.where_go",
    (I.GUIDE, "goal"): "request.where_take", (I.SAY, "object"): "request.what_say",
    (I.GUIDE, "recipient"): "request.who_take",
    (I.START_ACTIVITY, "object"): "request.which_activity",
}  # fmt: skip
#: What a question of ability may ask of a verb alone ("can you dance?", "can you cook?"): a skill.
_SKILLS = frozenset({I.PERFORM_MOTION, I.START_ACTIVITY})
#: Acts a correction of the request just made may read as ("make that the study": an activity;
#: "wait, no, on the bookcase": a refusal; "thanks! now the apple too": thanks): read as the
#: correction when one fits.
_CORRECTABLE = frozenset({"command", "negated", "thanks"})
_EXACTLY = {
    "object": "request.what_exactly", "recipient": "request.whom_exactly", "goal": "request.where_exactly",
}  # fmt: skip


class Interpreter:
    def __init__(
        self, lexicon: Lexicon, speaker: str, history: Sequence[Utterance] = (), robot_name: str = "robot"
    ) -> None:
        self.lexicon = lexicon
        self.lang = lexicon.lang
        self.snapshot = lexicon.snapshot
        self.speaker = speaker
        self.history = tuple(history)
        self.robot_name = robot_name
        self.refs = Referents(lexicon, speaker, self.history)

    def within(self, history: Sequence[Utterance]) -> Interpreter:
        """The same reader with another conversation before the words it reads."""
        return Interpreter(self.lexicon, self.speaker, history, self.robot_name)

    def interpret(self, text: Text) -> Outcome:
        said = Said.read(self.lang, text)
        said = said.rewritten(restarted(said.text))  # "the box of para- paracetamol"
        letters = said.rewritten(joined(said, self.lexicon))  # "the s u v brochure"
        spelled = corrected(letters, self.lexicon)
        heard = letters.rewritten(spelled.text, spelled.corrections)
        clean = cleaned(self.lang, heard)
        reader = self
        taken_back = heard.of(clean.taken_back) if clean.taken_back else None
        if taken_back is not None and parse(self.lang, taken_back, self.robot_name).act != "unknown":
            # "hand Ravi the uh no wait hand him the stapler": what was taken back is context
            context = (*self.history, Utterance(self.speaker, clean.taken_back))
            reader = Interpreter(self.lexicon, self.speaker, context, self.robot_name)
        outcome = reader._read(heard.of(clean.text))
        if heard.taken:
            # A corrected slip makes the whole turn less sure; a name read from a slip is a guess.
            steps = outcome.steps()
            unsure = [replace(o, confidence=min(o.confidence, SPELT_CONFIDENCE), more=()) for o in steps]
            outcome = replace(unsure[0], more=tuple(unsure[1:]), guessed=heard.guessed or outcome.guesses)
        # A reading without full evidence is never acted on: it is proposed ("Shall I ...?").
        return proposed(self.lang, outcome) if outcome.doubts and outcome.intent is not None else outcome

    def _read(self, heard: Said) -> Outcome:
        addressed = to_someone_else(self.lexicon, heard, self.speaker, self.robot_name)
        if addressed is not None:  # "lily put your book on the shelf": Lily is asked, not the robot
            return Outcome(say(self.lang, "request.for_someone_else", name=addressed))
        if accepts(self.lang, expanded(self.lang, heard)):  # "yes, please do": whole, not in parts
            accepted = follow_up(self, parse(self.lang, heard, self.robot_name), heard)
            if accepted is not None:
                return accepted
        for rest in self._from_each_clause(heard):  # the condition covers every part after it
            if self._conditioned(rest):  # ("if Ana comes, ...", "Ana phoned: when she comes, ...")
                whole = parse(self.lang, rest, self.robot_name)
                if whole.act == "conditional":
                    return self.act(whole)
        corrected = self._corrected(heard)
        if corrected is not None:
            return corrected
        parts = conjuncts(self.lang, heard)
        for rest in self._from_each_clause(heard):  # ("Milo's mum asked: the thermometer, give to Milo")
            before = heard.text[: len(heard.text) - len(rest.text)]
            more = parts or adds_on(self.lang, tuple(expanded(self.lang, rest)))
            if before and more and parse(self.lang, heard.of(before), self.robot_name).act == "command":
                break  # ("bring the tea to Ruby, then the bun to Kaur": both; "bring X please and then Y")
            said_terse = self._terse(rest)
            if said_terse is not None:
                return said_terse
        if parts:
            combined = compound(self, heard, parts)
            if combined is not None:
                return combined
        return self._single(heard, terse_read=False)  # (tried above, before the parts)

    def _corrected(self, heard: Said) -> Outcome | None:
        """ "Actually, make that the study", "wait, no, on the bookcase": a correction of the request
        just made, though its words read as an activity or a refusal of their own."""
        if not opens_correction(self.lang, heard):
            return None
        p = parse(self.lang, heard, self.robot_name)
        added = p.act == "unknown" and adds_one_more(self.lang, heard)
        return correction(self, p, heard) if p.act in _CORRECTABLE or added else None

    def _from_each_clause(self, heard: Said) -> list[Said]:
        """The words from the start of each clause to the end: the whole first."""
        text, out, at = heard.text, [heard], 0
        for i, clause in enumerate(clauses(self.lang, heard)):
            at = text.find(clause, at)
            if i > 0 and at > 0:
                out.append(heard.of(text[at:]))
        return out

    def _conditioned(self, heard: Said) -> bool:
        """Whether the words start with a condition ("if Ana comes", "when the bell goes")."""
        said = tuple(expanded(self.lang, heard))
        return said[:1] == ("if",) or bool(self.lang.derived(Grammar).conditions.of(said))

    def part(self, heard: Said) -> Outcome:
        """One part of a compound request, read as a request of its own."""
        return self._single(heard)

    def _terse(self, heard: Said) -> Outcome | None:
        """ "Orchid put on counter", "Go workstand", "dining room, now please": the request said in
        the grammar's order, when that is one (what was said is context: "Edna cardigan, put on
        her chair" is Edna's chair)."""
        last = self.history[-1] if self.history else None
        answering = last is not None and last.role != "user" and last.text.rstrip().endswith("?")
        said = terse(heard, self.lexicon, self.robot_name, answering)
        thing = None if said or answering else unasked_thing(heard, self.lexicon, self.robot_name)
        if said is None and thing is None:
            return None
        context = (*self.history, Utterance(self.speaker, heard.text))
        outcome = self.within(context)._single(heard.of(said or str(thing)), terse_read=False)
        if thing is not None:  # ("Water. Still.": the bottle of still water, proposed)
            outcome = replace(outcome, unsure=True)
        return outcome if outcome.intent is not None else None

    def _single(self, heard: Said, terse_read: bool = True) -> Outcome:
        if terse_read and (outcome := self._terse(heard)) is not None:
            return outcome
        p = parse(self.lang, heard, self.robot_name)
        # "go on then" to "Shall I fetch it?"
        if p.act != "unknown" and accepts(self.lang, expanded(self.lang, heard)):
            accepted = follow_up(self, p, heard)
            if accepted is not None:
                return accepted
        not_understood = Outcome(say(self.lang, "sorry.not_understood"), understood=False)
        # No act: an answer to the robot's question, or "sorry, I meant screen two" (`FOLLOW_UPS`)
        outcome = followed_up(self, p, heard) or not_understood if p.act == "unknown" else self.act(p)
        # "can you dance?": maybe only asked
        if outcome.intent in _SKILLS and asks_ability(self.lang, heard, p, self.robot_name):
            outcome = replace(outcome, unsure=True)
        ungrounded = p.act == "command" and outcome.intent is None and not outcome.clarify
        failed = not outcome.understood or ungrounded
        return self._clause_by_clause(heard, outcome) if failed else outcome

    def _unaccounted(self, intent: str, slots: dict[str, Words]) -> bool:
        """Whether a phrase the intent grounds no role of names someone ("salute Olu in the meeting
        room", "water jug to Edith"): words the reading cannot account for."""
        grounded = ROLE_KINDS.get(intent, {})
        if intent == I.STOP_ACTIVITY:  # whatever is said to be stopped, the robot stops
            return False
        for role, words in slots.items():
            if role in grounded or role == "rest":
                continue
            words = words[: words.index("for")] if "for" in words else words  # ("the tour for Jonas": his)
            named = (resolve(self.lexicon, (w,), PERSON).one for w in content_words(self.lang, words))
            if any(person is not None for person in named):
                return True
        return False

    def _clause_by_clause(self, heard: Said, whole: Outcome) -> Outcome:
        """ "The denim jacket. Pick it up." or "Felix wants the remote, can you hand it to him?": when
        the whole utterance is not one request, the last clause that is one is read with the clauses
        before it as context for its pronouns."""
        said = clauses(self.lang, heard)
        if len(said) < 2:
            return whole
        question: Outcome | None = None
        failed: Outcome | None = None
        for i in range(len(said) - 1, -1, -1):
            context = tuple(Utterance(self.speaker, c) for c in said[:i])
            reader = Interpreter(self.lexicon, self.speaker, (*self.history, *context), self.robot_name)
            p = parse(self.lang, heard.of(said[i]), self.robot_name)
            if p.act in {"command", "question"}:
                # "fetch my bag its the blue one": what the next clause says of the thing asked for
                more = None
                if i + 1 < len(said) and p.slots.get("object"):
                    more = description(self.lang, heard.of(said[i + 1]))
                with_more = {"object": described(self.lang, p.slots["object"], more)} if more else None
                outcome = reader.act(p, with_more)
                if outcome.intent is not None:
                    return wished(self, heard, said[:i], outcome)
                # A complete request in an earlier clause beats asking about an incomplete later one.
                if question is None and (outcome.clarify or (p.act == "question" and outcome.understood)):
                    question = outcome
                # Why a request alone fails says it better than the run-on whole ("...the sink theres a
                # spill": no sink, not no "sink spill").
                elif p.act == "command" and outcome.understood and not outcome.clarify:
                    failed = outcome
        return question or said_first(self, heard, said) or failed or whole

    def act(self, p: Parse, overrides: dict[str, Words] | None = None) -> Outcome:
        """What the parse's act is read as (`ACTS`): social talk, a question, a request."""
        read = ACTS.get(p.act)
        if read is None:
            return Outcome(say(self.lang, "sorry.not_understood"), understood=False)
        return read(self, p, overrides or {})

    # -- questions -------------------------------------------------------------------------------
    def _question(self, p: Parse, overrides: dict[str, Words]) -> Outcome:
        answer = situation.answer(self, p)
        if not p.greeted or not answer.understood or answer.clarify:
            return answer
        # "hello robot, what's your name": both
        greeting = hello(self.lang, self.snapshot, self.speaker)
        return self._intent(I.GREET, {"recipient": self.speaker}, f"{greeting} {answer.reply}")

    # -- commands --------------------------------------------------------------------------------
    def _command(self, p: Parse, overrides: dict[str, Words]) -> Outcome:
        if p.intent is None:
            return Outcome(say(self.lang, "sorry.not_understood"), understood=False)
        whole = unskilled(self.lang, p) or left_as_is(self, p) or self._one_command(p, overrides)
        # "bring me the bread and the jam", "greet Ana and Tom": one intent per thing or person
        # named, in order (people only where a role is a person's: one cup goes to one person).
        role = "object" if "object" in p.slots else "recipient"
        person = ROLE_KINDS.get(p.intent or "", {}).get("recipient") == PERSON
        things = coordinated(self.lang, p.slots.get(role, ())) if role not in overrides else []
        if role == "recipient" and not person:
            things = []
        if role == "object" and not things and role not in overrides:
            things = self.refs.every(p.slots.get(role, ()))  # "all the plates": each plate there is
        if whole.clarify or not things or (whole.intent is not None and len(things) == 1):
            return whole
        if len(things) == 1:
            return self._one_command(p, {**overrides, role: things[0]})
        each = [self._one_command(p, {**overrides, role: t}) for t in things]
        if whole.intent is not None and not two_named(self.lang, self.snapshot, role, (whole, *each)):
            return whole
        if any(o.intent is None for o in each):
            return next(o for o in each if o.intent is None)
        return replace(each[0], reply=then(self.lang, [o.reply for o in each]), more=tuple(each[1:]))

    def _one_command(self, p: Parse, overrides: dict[str, Words]) -> Outcome:  # noqa: C901
        intent = p.intent or ""
        slots = {**p.slots, **overrides}
        if "object" not in overrides:  # ("the key card for room 309": one name, not a recipient)
            slots, marks = self.refs.named_across(slots, p.marks)
            p = replace(p, marks=marks)
        if p.double_object and "rest" in slots:
            slots = {**self.refs.split_double_object(slots.pop("rest")), **overrides}
        if intent in {I.BRING_OBJECT, I.PLACE_OBJECT} and "recipient" in slots:
            # "take Maria to the kitchen", "walk Mr Ito back to the car park": guiding, not carrying
            who = tuple(w for w in slots.get("object", ()) if w not in relational(self.lang))
            # (never to a person: "take them to her" carries them to her)
            if self.refs.person_as_object(who) is not None and who:
                to = slots["recipient"]
                if self.refs.a_person(to) or to in self.lang.requests.brought_here:
                    # "bring Sam here": a person brought to a person is no intent the rules have
                    return Outcome(say(self.lang, "sorry.not_understood"), understood=False)
                intent, slots = I.GUIDE, {"recipient": who, "goal": slots["recipient"]}
            elif intent == I.PLACE_OBJECT and (
                self.refs.named_person(slots["recipient"]) or self.refs.an_owner(slots["recipient"])
            ):
                intent = I.BRING_OBJECT  # "return the stapler to Carol", "... to its owner": to a person
        if intent == I.BRING_OBJECT and self.refs.a_place(slots.get("object", ())):
            # "I need the lifts": a place is where to be taken, not a thing to carry
            intent, slots = I.GUIDE, {"recipient": slots.get("recipient", ("me",)), "goal": slots["object"]}
        if intent == I.GUIDE and self.refs.someone_else(slots.get("goal", ())):
            # "take me to Marcus", "take me to him": to where he is (unknown: no place, said so by
            # the grounding)
            person = self.refs.person_as_object(slots["goal"])
            if person is not None and person.zone and not self.refs.a_place(slots["goal"]):
                slots["goal"] = tuple(tokens(person.zone))
        if intent == I.GUIDE and "goal" in p.implicit and "goal" not in overrides:
            there = antecedent(self.lexicon, self.history, PLACE, place=True, speaker=self.speaker)
            if there is None:  # "take me", "escort Carla", with no place spoken of: asked (whom named)
                slots.pop("goal", None)
        if intent == I.GREET and "recipient" in p.implicit and "recipient" not in overrides:
            # "this is Callum, say hello": whom the same utterance introduced, else the speaker
            person = antecedent(self.lexicon, self._this_turn(), PERSON, speaker=self.speaker)
            slots["recipient"] = tuple(tokens(person.id)) if person is not None else ("me",)
        implicit = "recipient" in p.implicit or not content_words(self.lang, slots.get("recipient", ()))
        if intent == I.GUIDE and slots.get("goal") == ("there",) and implicit:
            # "Ellen needs the utility room, lead the way": the person just spoken of, else the speaker.
            person = antecedent(self.lexicon, self.history, PERSON, speaker=self.speaker)
            slots["recipient"] = tuple(tokens(person.id)) if person is not None else ("me",)
        if "object" in slots:  # "I need biscuits, can you get me some": some of those
            slots["object"] = self.refs.some_of(slots["object"])
        roles: dict[str, str] = {}
        refs: dict[str, Ref] = {}
        mine: list[Entity] = []  # things said to be the speaker's ("my book")
        spec = I.CATALOGUE[intent]
        for role, kinds in ROLE_KINDS.get(intent, {}).items():
            words = slots.get(role, ())
            if not content_words(self.lang, words) and words not in self.lang.requests.said_there:
                if role in spec.required and set(words) & self.lang.words.demonstratives:
                    # "bring me that one": what is pointed at, which the words do not say
                    return Outcome(say(self.lang, "sorry.not_understood"), understood=False)
                if role in spec.required:
                    return self._missing(intent, role, p, roles.get("recipient"))
                continue
            if content_words(self.lang, words)[:1] in ([w] for w in self.lang.words.indefinite):
                # "guide somebody there", "put it somewhere safe": who or where is asked
                return self._missing(intent, role, p, roles.get("recipient"))
            owned = self.refs.possessive(words, slots) if role == "object" else whose(self, words, kinds)
            words, owner = owned
            others = [w for r, w in slots.items() if r != role]
            ref = ground(self.refs, words, kinds, role, owner, others)
            if ref.problem is not None:
                return none_yours(self, ref.problem, words, kinds) if owner == self.speaker else ref.problem
            refs[role] = ref
            roles[role] = self.speaker if ref.speaker else (ref.entity.id if ref.entity else "")
            # "my stapler" (not "the folder on my desk": whose the desk is)
            said_mine = slots.get(role, ())[:1] == (self.lang.words.owners.get("mine"),)
            if said_mine and owner == self.speaker and ref.entity is not None and ref.entity.kind == "thing":
                mine.append(ref.entity)
        if p.text is not None:
            roles["object"] = p.text
        elif intent in {I.SAY, I.START_ACTIVITY, I.PERFORM_MOTION, I.PRESENT_CONTENT}:
            return self._missing(intent, "object", p)
        # The place said back with the preposition it was said with, unless a part of it was named
        # ("in the centre of the table" is put on the table).
        place = slots.get("recipient", ())
        mark = p.marks.get("recipient")
        part_named = set(place) & self.lang.words.parts and "of" in place
        said = " ".join(mark) if mark is not None and not part_named else None
        intent = carried_onto(self.lang, self.snapshot, p, intent, roles)  # "take it to the table"
        reply = acknowledgement(self.lang, self.snapshot, self.speaker, intent, roles, refs, said,
                                self.lexicon.shares_name)
        if intent == I.GREET and roles.get("recipient") == self.speaker:  # "say hello": to the speaker
            reply = hello(self.lang, self.snapshot, self.speaker)
        notes = [whose_it_is(self.lang, self.snapshot, e, self.speaker)
                 for e in mine if e.owner != self.speaker]  # fmt: skip
        reply = " ".join([*notes, reply])  # "my book" that is Marcus's: said before acting
        if any(ref.guessed for ref in refs.values()):  # "go to bay mine": a guess, less sure
            return Outcome(reply, intent, roles, SPELT_CONFIDENCE, guessed=True)
        return replace(self._intent(intent, roles, reply), unsure=self._unaccounted(intent, slots))

    def _this_turn(self) -> tuple[Utterance, ...]:
        """What the speaker said since the robot last spoke (the earlier clauses of this turn)."""
        said = [i for i, u in enumerate(self.history) if u.role == "assistant"]
        return self.history[said[-1] + 1 :] if said else self.history

    def _missing(self, intent: str, role: str, p: Parse, whom: str | None = None) -> Outcome:
        # ("show Ana in": where to take her, not "you")
        you = whom in {None, self.speaker}
        them = say(self.lang, "naming.you") if you else self.snapshot.name_of(whom or "")
        key = _ASKED.get((intent, role)) or _EXACTLY.get(role, "request.what_exactly")
        return Outcome(say(self.lang, key, whom=them), clarify=True, open_role=role)

    def _intent(self, intent: str, roles: dict[str, str], reply: str, confidence: float = 0.9) -> Outcome:
        return Outcome(reply, intent, roles, confidence)


#: How each act the grammar reads is understood (an act not here is not: "unknown").
ACTS: dict[str, Callable[[Interpreter, Parse, dict[str, Words]], Outcome]] = {
    **TALK, "question": Interpreter._question, "command": Interpreter._command,
}  # fmt: skip
