"""Learning what a person says: their belief first, then (by the trust policy) the robot's knowledge.

For every statement of a turn, in this order:

1. **Their belief.** The fact goes into the speaker's own model (knowledge_core's per-agent models,
   `models=[<speaker>]`), replacing what they believed before in its place (a new name, a new place,
   the opposite preference).
2. **Adoption.** The trust policy says whether the robot also takes it as true: `all`, `none`, or
   `people` (the default): what a person says about themself ("I'm Bob", "I like tea"), their own
   things ("the red mug is mine", "I left my glasses on the sofa"; a thing is theirs by a
   `belongsTo` the robot knows or one said in the same turn), and the name of someone the robot
   cannot name, or could only by that person's word ("this is Maria", then "no, it's Marta").
3. **Perception wins.** An adopted fact is checked against the robot's model: a value of the same
   place (its name, owner, location, or the opposite preference) asserted there without a record of
   having been told is perception's (or another producer's), and dialogue never overwrites it: the
   statement stays the speaker's belief and the reply says what the robot knows instead. A value
   that was itself told is replaced, record and all — unless it is someone else's word about what
   is someone else's (dialogue.memory.disputes): a thing another person's word made theirs, or the
   name of another known person, which stays the speaker's belief under every policy.
4. **Provenance.** Every adopted fact gets its record (dialogue.memory.provenance), written in the
   same commit as the fact.

One turn's statements are one commit (`apply_models`): the speaker's model and the robot's change
together, or, refused (a full disk, the store down), neither does.

Questions ("what does Alice like?") are answered from the robot's model, and from what others said
(their models) when the robot has not adopted it. Everything here reads and writes the KB: call it
off the event loop.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from datetime import UTC, datetime
from enum import StrEnum
from typing import Literal as Status

from rdflib import Literal, URIRef

from dialogue.memory.claims import BY_PROPERTY, Claim
from dialogue.memory.disputes import dispute
from dialogue.memory.kinds import find_kind
from dialogue.memory.provenance import Fact, forget, record, record_of
from dialogue.reference.grounding import Snapshot
from kb.models import DEFAULT_MODEL
from kb.protocol import KnowledgeBase
from kb.terms import Node, format_term, format_triple, parse_name

#: Other people's models asked when answering a question (the robot's model is asked first).
MAX_HEARSAY_MODELS = 50


class Trust(StrEnum):
    """Whose statements the robot adopts into its own model (the others stay beliefs)."""

    ALL = "all"
    PEOPLE = "people"
    NONE = "none"


Outcome_ = Status["adopted", "known", "believed", "perceived", "disputed", "unknown", "answered"]


@dataclass(frozen=True)
class Outcome:
    """What became of one claim. `object` is the resolved object (an id, a class id or a name)."""

    claim: Claim
    status: Outcome_
    object: str | None = None
    #: The robot's values that win over the claim (perception's, or another person's word) as
    #: (property, value), or the values a question found.
    held: tuple[tuple[str, str], ...] = ()
    #: Told values the claim replaced ("no, it's Rob": ("Bob",)).
    replaced: tuple[str, ...] = ()
    #: For a question the robot's model does not answer: (who said it, value) from their models;
    #: for a disputed claim, whose word holds: (who told it, or has the name, value).
    hearsay: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True)
class Settled:
    outcomes: tuple[Outcome, ...]
    #: Names of the kinds and values the outcomes mention (class ids -> "tea").
    names: dict[str, str] = field(default_factory=dict)


def _now() -> datetime:
    return datetime.now(UTC)


def _term(value: str, literal: bool) -> Node:
    return Literal(value) if literal else parse_name(value, "value")


class Memory:
    """Learns claims into a KB under a trust policy; answers questions about what it learnt."""

    def __init__(self, kb: KnowledgeBase, trust: Trust | str = Trust.PEOPLE,
                 clock: Callable[[], datetime] = _now) -> None:
        self.kb = kb
        self.trust = Trust(trust)
        self.clock = clock
        # One learner at a time: two turns telling values of the same place at once would each
        # read the other's as absent.
        self._lock = threading.Lock()

    def settle(self, claims: Sequence[Claim], *, speaker: str, text: str, snapshot: Snapshot) -> Settled:
        """Learn the statements and answer the questions of one turn (blocking: KB reads and at
        most one write, the speaker's model and the robot's together). KbError when the KB
        refuses, and then nothing was learnt."""
        with self._lock:
            return self._settle(claims, speaker, text, snapshot)

    def _settle(self, claims: Sequence[Claim], speaker: str, text: str, snapshot: Snapshot) -> Settled:
        names: dict[str, str] = {}
        resolved: list[Outcome] = []
        for claim in claims:
            if claim.form == "kind" and claim.object is not None:
                kind = find_kind(self.kb, claim.object)
                if kind is None and claim.fallback is None:
                    resolved.append(Outcome(claim, "unknown", claim.object))
                    continue
                if kind is not None:
                    names[kind.id] = claim.object  # as told: "apples" for the class "apple"
                found = kind.id if kind is not None else claim.fallback
                claim = replace(claim, object=found, form="entity", fallback=None)
            resolved.append(Outcome(claim, "answered" if claim.asks else "known", claim.object))
        tells = [o.claim for o in resolved if o.status == "known"]
        decided, add, remove = self._adopt(speaker, text, tells, snapshot)
        changes: dict[str, tuple[list[str], list[str]]] = {}
        if tells:
            changes[speaker] = self._belief(speaker, tells)
        if add or remove:
            before = changes.get(DEFAULT_MODEL, ([], []))
            changes[DEFAULT_MODEL] = ([*before[0], *add], [*before[1], *remove])
        if changes:
            self.kb.apply_models({name: {"add": a, "remove": r} for name, (a, r) in changes.items()})
        out = []
        for outcome in resolved:
            if outcome.status == "answered":
                outcome = self._answer(outcome.claim, names)
            elif outcome.status == "known":
                outcome = decided[outcome.claim]
            out.append(outcome)
        return Settled(tuple(out), names)

    # -- the speaker's belief ---------------------------------------------------------------------
    def _belief(self, speaker: str, tells: Sequence[Claim]) -> tuple[list[str], list[str]]:
        """The changes of the speaker's own model: the told values, replacing theirs before."""
        model = [speaker]
        known = speaker in self.kb.models()
        add, remove = [], []
        for claim in tells:
            fact = _fact(claim)
            add.append(format_triple(fact))
            if known:
                remove += [format_triple(f) for f in self._held(claim, model) if f != fact]
        return add, remove

    # -- adoption into the robot's model ------------------------------------------------------------
    def _trusted(self, speaker: str, claim: Claim, theirs: set[str]) -> bool:
        if self.trust is Trust.ALL:
            return True
        if self.trust is Trust.NONE:
            return False
        if claim.subject == speaker:
            return True
        if claim.predicate == "belongsTo":
            return claim.object == speaker
        if claim.predicate == "name":  # an introduction ("this is Maria"), or its correction by its teller
            held = self._held(claim, [DEFAULT_MODEL])
            return all(self._was_told(f, by=speaker) for f in held)
        return claim.subject in theirs

    def _adopt(self, speaker: str, text: str, tells: Sequence[Claim],
               snapshot: Snapshot) -> tuple[dict[Claim, Outcome], list[str], list[str]]:
        """What becomes of each claim in the robot's model, and that model's changes (add, remove)."""
        owned = [c.subject for c in tells if c.predicate == "belongsTo" and c.object == speaker]
        # Only the told subjects are ever asked about: no pass over every entity of the snapshot.
        subjects = (snapshot.get(c.subject) for c in tells)
        theirs = {e.id for e in subjects if e is not None and e.owner == speaker} | set(owned)
        when = self.clock()
        who = parse_name(speaker, "speaker")
        add: list[str] = []
        remove: list[str] = []
        decided: dict[Claim, Outcome] = {}
        for claim in tells:
            if not self._trusted(speaker, claim, theirs):
                decided[claim] = Outcome(claim, "believed", claim.object)
                continue
            fact = _fact(claim)
            held = self._held(claim, [DEFAULT_MODEL])
            told = {f for f in held if self._was_told(f)}
            perceived = [f for f in held if f not in told and not self._within(f, fact)]
            if fact in perceived:
                decided[claim] = Outcome(claim, "known", claim.object)
                continue
            if perceived:
                values = tuple((_shown(f[1]), _shown(f[2])) for f in perceived)
                decided[claim] = Outcome(claim, "perceived", claim.object, held=values)
                if claim.predicate == "belongsTo" and claim.subject in theirs and claim.subject in owned:
                    theirs.discard(claim.subject)  # not theirs after all: their places stay beliefs
                continue
            replaced = [f for f in told if f != fact]
            disputed = dispute(self.kb, claim, speaker, replaced)
            if disputed is not None:  # someone else's word holds: the claim stays the speaker's belief
                holds = (disputed.property, disputed.value)
                decided[claim] = Outcome(claim, "disputed", claim.object, held=(holds,),
                                         hearsay=((disputed.by, disputed.value),))
                if claim.predicate == "belongsTo":
                    theirs.discard(claim.subject)  # not theirs after all: their places stay beliefs
                continue
            for old in [*replaced, *([fact] if fact in told else [])]:
                remove += forget(self.kb, old)
            remove += [format_triple(f) for f in replaced]
            add += [format_triple(fact), *record(fact, who, when, text)]
            status: Outcome_ = "known" if fact in told else "adopted"
            replaced_values = tuple(_shown(f[2]) for f in replaced)
            decided[claim] = Outcome(claim, status, claim.object, replaced=replaced_values)
        return decided, add, [r for r in remove if r not in add]

    def _held(self, claim: Claim, models: list[str]) -> list[Fact]:
        """The asserted facts of `models` in the claim's place: the values a new one replaces."""
        spec = claim.spec
        subject = parse_name(claim.subject, "subject")
        out: list[Fact] = []
        for prop in spec.replaces:
            predicate = parse_name(prop, "predicate")
            literal = BY_PROPERTY[prop].objects is None
            if spec.per_object:
                values: Iterable[str] = [claim.object] if claim.object is not None else []
            else:
                rows = self.kb.find([f"{format_term(subject)} {prop} ?v"], models=models)
                values = [str(r["v"]) for r in rows]
            for value in values:
                fact = (subject, predicate, _term(value, literal))
                if self.kb.is_asserted(format_triple(fact), models[0]):
                    out.append(fact)
        return out

    def _within(self, held: Fact, fact: Fact) -> bool:
        """A perceived zone that holds the told place ("in the kitchen" and "in the drawer", the
        drawer being in the kitchen) is no contradiction: the told place is more precise."""
        if format_term(held[1]) != "isIn" or held[2] == fact[2]:
            return False
        return self.kb.exist([f"{format_term(fact[2])} isIn {format_term(held[2])}"])

    def reconcile(self, subject: str, prop: str, value: str, literal: bool = False) -> int:
        """Perception wins afterwards too: when a value perceived (asserted without a record)
        contradicts told ones of the same place, the told ones go, with their records. The number
        of told facts retracted (blocking; KbError when the KB refuses)."""
        spec = BY_PROPERTY.get(prop)
        if spec is None:
            return 0
        claim = Claim(subject, spec.name, value, "text" if literal else "entity")
        with self._lock:
            fact = _fact(claim)
            if not self.kb.is_asserted(format_triple(fact)) or self._was_told(fact):
                return 0  # gone again, or told itself: nothing perceived to win
            stale = [f for f in self._held(claim, [DEFAULT_MODEL])
                     if f != fact and self._was_told(f) and not self._within(fact, f)]
            if stale:
                self.kb.apply([], [s for f in stale for s in (*forget(self.kb, f), format_triple(f))])
            return len(stale)

    def forget_if_gone(self, subject: str, prop: str, value: str, literal: bool = False) -> bool:
        """Retract the record of a told fact that is no longer asserted (whoever retracted it);
        True when there was one (blocking; KbError when the KB refuses)."""
        spec = BY_PROPERTY.get(prop)
        if spec is None:
            return False
        with self._lock:
            fact = _fact(Claim(subject, spec.name, value, "text" if literal else "entity"))
            if self.kb.is_asserted(format_triple(fact)) or not self._was_told(fact):
                return False  # told again since, or its record went with it
            self.kb.apply([], forget(self.kb, fact))
            return True

    def _was_told(self, fact: Fact, by: str | None = None) -> bool:
        who = format_term(parse_name(by, "speaker")) if by is not None else "?who"
        return self.kb.exist([f"{format_term(record_of(fact))} toldBy {who}"])

    # -- questions --------------------------------------------------------------------------------
    def _answer(self, claim: Claim, names: dict[str, str]) -> Outcome:
        """The question's answer; a property whose value replaces the one asked about answers it too
        (one place: where a thing is, asked as isIn, found as isOn, "Ana told me the diary is on the
        shelf"; not an opposite, per object: "what does Ana like?" is not answered by her dislikes)."""
        outcome = self._answer_one(claim, names)
        others = () if claim.spec.per_object else claim.spec.replaces
        for prop in (p for p in others if p != claim.predicate):
            if outcome.held or outcome.hearsay:
                break
            outcome = self._answer_one(replace(claim, predicate=prop), names)
        return outcome

    def _answer_one(self, claim: Claim, names: dict[str, str]) -> Outcome:
        prop = claim.spec.property
        pattern = f"{format_term(parse_name(claim.subject, 'subject'))} {prop} ?v"
        held = tuple(sorted({(prop, str(r["v"])) for r in self.kb.find([pattern])}))
        hearsay: list[tuple[str, str]] = []
        if not held:
            others = [m for m in self.kb.models() if m != DEFAULT_MODEL][:MAX_HEARSAY_MODELS]
            hearsay = [(m, str(r["v"])) for m in others for r in self.kb.find([pattern], models=[m])]
        for value in (*(v for _, v in held), *(v for _, v in hearsay)):
            if claim.spec.objects is not None and value not in names:
                names[value] = self.kb.label(value)
        return Outcome(claim, "answered", held=held, hearsay=tuple(hearsay))


def _fact(claim: Claim) -> Fact:
    assert claim.object is not None  # statements only
    subject = parse_name(claim.subject, "subject")
    predicate = parse_name(claim.spec.property, "predicate")
    return subject, predicate, _term(claim.object, claim.form == "text")


def _shown(term: Node) -> str:
    """A fact's object as `find` shows it: an id, or the literal's text."""
    if isinstance(term, URIRef):
        return format_term(term)
    return str(term)
