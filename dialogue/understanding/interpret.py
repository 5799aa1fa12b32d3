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
from dialogue.reference.english import Words
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.resolution import PERSON, ROLE_KINDS
from dialogue.understanding.followups.accepting import accepts
from dialogue.understanding.followups.correction import corrected_first
from dialogue.understanding.followups.proposal import proposed
from dialogue.understanding.followups.request import follow_up, followed_up, said_first
from dialogue.understanding.outcome import SPELT_CONFIDENCE, Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.questions import situation
from dialogue.understanding.replies import hello, say, then
from dialogue.understanding.requests.abilities import asks_ability
from dialogue.understanding.requests.addressed import to_someone_else
from dialogue.understanding.requests.commands import parse
from dialogue.understanding.requests.compound import adds_on, conjuncts, coordinated, two_named
from dialogue.understanding.requests.referents import Referents
from dialogue.understanding.requests.roles import one_command
from dialogue.understanding.requests.sequence import compound, dropped, wished
from dialogue.understanding.requests.skills import no_intent, unskilled
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

#: What a question of ability may ask of a verb alone ("can you dance?", "can you cook?"): a skill.
_SKILLS = frozenset({I.PERFORM_MOTION, I.START_ACTIVITY})
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
        """ "Actually, make that the study", "wait, no, on the bookcase", "oh and the biscuits too": a
        correction of the request just made, or one more for it, read before its words alone."""
        return corrected_first(self, parse(self.lang, heard, self.robot_name), heard)

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
        # No act: an answer to the robot's question (`FOLLOW_UPS`), else an action with no intent
        outcome = self.act(p) if p.act != "unknown" else (
            followed_up(self, p, heard) or no_intent(self.lang, p) or not_understood)
        # "can you dance?": maybe only asked
        if outcome.intent in _SKILLS and asks_ability(self.lang, heard, p, self.robot_name):
            outcome = replace(outcome, unsure=True)
        ungrounded = p.act == "command" and outcome.intent is None and not outcome.clarify
        failed = not outcome.understood or ungrounded
        return self._clause_by_clause(heard, outcome) if failed else outcome

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
                outcome = dropped(reader, heard.of(said[i]), said[:i], reader.act(p, with_more))
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
        whole = unskilled(self.lang, p) or left_as_is(self, p) or one_command(self, p, overrides)
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
            return one_command(self, p, {**overrides, role: things[0]})
        each = [one_command(self, p, {**overrides, role: t}) for t in things]
        if whole.intent is not None and not two_named(self.lang, self.snapshot, role, (whole, *each)):
            return whole
        if any(o.intent is None for o in each):
            return next(o for o in each if o.intent is None)
        return replace(each[0], reply=then(self.lang, [o.reply for o in each]), more=tuple(each[1:]))

    def _intent(self, intent: str, roles: dict[str, str], reply: str, confidence: float = 0.9) -> Outcome:
        return Outcome(reply, intent, roles, confidence)


#: How each act the grammar reads is understood (an act not here is not: "unknown").
ACTS: dict[str, Callable[[Interpreter, Parse, dict[str, Words]], Outcome]] = {
    **TALK, "question": Interpreter._question, "command": Interpreter._command,
}  # fmt: skip
