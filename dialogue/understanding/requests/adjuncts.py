"""The adjuncts of a request: the phrases that say how, when or by which way ("through the main
door", "on my behalf", "when you can", "carefully", "for now"), understood and part of no role's
phrase (dialogue.understanding.requests.commands reads the roles from what is left)."""

from __future__ import annotations

from dialogue.reference.english import Words
from dialogue.understanding.requests.frames import Row
from dialogue.understanding.requests.vocabulary import Grammar


def adjuncts_of(g: Grammar, rest: Words, row: Row) -> tuple[Words, tuple[Words, ...]]:
    """The words without their adjuncts ("through the main door", "on my behalf", "when you can",
    "carefully"), and the adjuncts. A phrase starting with one of the row's own prepositions is
    one of its roles, not an adjunct."""
    own = {m[0][0] for m in row.slots}
    out: list[str] = []
    found: list[Words] = []
    i = 0
    while i < len(rest):
        end = _adjunct_end(g, rest, i, own)
        if end > i:
            found.append(rest[i:end])
            i = end
        else:
            out.append(rest[i])
            i += 1
    return tuple(out), tuple(found)


def _adjunct_end(g: Grammar, rest: Words, i: int, own: set[str]) -> int:
    word = rest[i]
    lasting = len(g.durations.first(rest, i) or ())
    if lasting:  # "wait in the hall for now", "bring the fan for now"
        return i + lasting
    by_doing = word == "by" and i + 1 < len(rest) and rest[i + 1].endswith("ing")  # "by crossing the hall"
    # "down the hall to the garage": the way, when the place comes after it
    way = word in g.goal_particles & own and bool(set(rest[i + 1 :]) & (own - g.goal_particles))
    # "take Aisha down the corridor to the staff room": the way, between the thing or person and
    # where they go, for a verb of carrying or guiding too
    particle = i > 0 and word in g.goal_particles
    way = way or (particle and rest[i + 1 : i + 2] != () and rest[i + 1] in g.np_start
                  and bool(set(rest[i + 2 :]) & (own - g.goal_particles)))  # fmt: skip
    if word in own and not by_doing and not way:
        return i
    said_how = _said_how(g, rest, i)
    if said_how:
        return i + said_how
    if word in g.paths or by_doing or way:
        end, stop = i + 1, (own - g.goal_particles) | g.paths
        while end < len(rest) and rest[end] not in stop and not _said_how(g, rest, end):
            end += 1
        # "through the main door" has a phrase; "walk through to the lounge" is a particle.
        return end if end > i + 1 else i
    return i


def _said_how(g: Grammar, rest: Words, i: int) -> int:
    """The length of the phrase of manner or time that starts at i ("when you can", "carefully", a
    clause of time to the end: "while he waits"), or 0."""
    if rest[i] in g.manner:
        return 1
    subject = rest[i + 1] if i + 1 < len(rest) else ""
    if i > 0 and (rest[i] in g.while_ or (rest[i] in g.time_conjunctions and subject in g.their_subjects)):
        return len(rest) - i
    return next((len(p) for p in g.adjuncts_by_first.get(rest[i], ()) if rest[i : i + len(p)] == p), 0)
