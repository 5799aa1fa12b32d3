"""Learning: the speaker's belief, the trust policy, perception wins, provenance, questions."""

from __future__ import annotations

from datetime import UTC, datetime

import pytest

from dialogue.memory.claims import Claim
from dialogue.memory.learn import Memory, Settled, Trust
from dialogue.memory.provenance import told
from kb import KB, KbError
from tests.dialogue.memory.conftest import snapshot_of

BOB = "person_bob"
WHEN = datetime(2025, 6, 1, 10, 30, tzinfo=UTC)


def settle(kb: KB, *claims: Claim, trust: Trust = Trust.PEOPLE, speaker: str = BOB,
           text: str = "words") -> Settled:
    return Memory(kb, trust, clock=lambda: WHEN).settle(claims, speaker=speaker, text=text,
                                                        snapshot=snapshot_of(kb))


def statuses(settled: Settled) -> list[str]:
    return [o.status for o in settled.outcomes]


def holds(kb: KB, statement: str, model: str = "default") -> bool:
    return kb.is_asserted(statement, model)


def test_a_statement_is_first_the_speakers_belief_whatever_the_policy(home: KB) -> None:
    before = home.size("default", inferred=False)
    settled = settle(home, Claim("phone_1", "belongsTo", "person_ines"), trust=Trust.NONE)
    assert statuses(settled) == ["believed"]
    assert holds(home, "phone_1 belongsTo person_ines", BOB)
    assert not holds(home, "phone_1 belongsTo person_ines")
    assert home.size("default", inferred=False) == before  # the robot's model did not change


def test_the_people_policy_adopts_what_people_say_of_themselves_and_their_things(home: KB) -> None:
    settled = settle(home, Claim(BOB, "name", "Bob", "text"), Claim("mug_red", "belongsTo", BOB),
                     Claim("mug_red", "isOn", "sofa_1"), Claim("phone_1", "belongsTo", "person_ines"),
                     Claim("person_alice", "likes", "tea", "kind"))
    assert statuses(settled) == ["adopted", "adopted", "perceived", "believed", "believed"]
    assert holds(home, f'{BOB} rdfs:label "Bob"') and holds(home, f"mug_red belongsTo {BOB}")
    assert not holds(home, "phone_1 belongsTo person_ines") and not holds(home, "person_alice likes dbr:Tea")
    # The mug is Bob's, so where it is would be adopted too, but the robot sees it on the table.
    assert not holds(home, "mug_red isOn sofa_1") and holds(home, "mug_red isOn table_1")
    assert holds(home, "mug_red isOn sofa_1", BOB)


def test_an_introduction_of_someone_the_robot_cannot_name_is_adopted(home: KB) -> None:
    assert statuses(settle(home, Claim("person_x", "name", "Maria", "text"))) == ["adopted"]
    assert statuses(settle(home, Claim("person_alice", "name", "Ally", "text"))) == ["believed"]


def test_who_introduced_someone_may_correct_the_name_they_gave(home: KB) -> None:
    settle(home, Claim("person_x", "name", "Maria", "text"))
    assert statuses(settle(home, Claim("person_x", "name", "Marta", "text"))) == ["adopted"]
    assert [r["l"] for r in home.find(['person_x rdfs:label ?l'])] == ["Marta"]
    # Someone else may not: the robot has the name from Bob.
    assert statuses(settle(home, Claim("person_x", "name", "Mia", "text"), speaker="person_ines")) == ["believed"]


def test_all_adopts_everything_perception_does_not_contradict(home: KB) -> None:
    settled = settle(home, Claim("phone_1", "belongsTo", "person_ines"), Claim("person_alice", "likes", "tea", "kind"),
                     Claim("keys_1", "isIn", "drawer_1"), trust=Trust.ALL)
    assert statuses(settled) == ["adopted", "adopted", "adopted"]
    assert holds(home, "person_alice likes dbr:Tea")
    # The drawer is in the kitchen, where the robot last saw the keys: more precise, no contradiction.
    assert holds(home, "keys_1 isIn drawer_1") and holds(home, "keys_1 isIn kitchen")


def test_perception_wins_and_the_outcome_says_what_the_robot_knows(home: KB) -> None:
    settled = settle(home, Claim("remote_1", "isIn", "drawer_1"), Claim("book_1", "belongsTo", BOB),
                     trust=Trust.ALL)
    assert statuses(settled) == ["perceived", "perceived"]
    assert settled.outcomes[0].held == (("isOn", "sofa_1"),)
    assert settled.outcomes[1].held == (("belongsTo", "person_alice"),)
    assert holds(home, "remote_1 isOn sofa_1") and not holds(home, "remote_1 isIn drawer_1")
    assert holds(home, "remote_1 isIn drawer_1", BOB)  # Bob still believes it


def test_a_told_value_is_replaced_with_its_record(home: KB) -> None:
    settle(home, Claim(BOB, "name", "Bob", "text"), text="I'm Bob")
    settled = settle(home, Claim(BOB, "name", "Rob", "text"), text="no, it's Rob")
    assert statuses(settled) == ["adopted"] and settled.outcomes[0].replaced == ("Bob",)
    assert [r["l"] for r in home.find(f"{BOB} rdfs:label ?l")] == ["Rob"]
    assert [r["l"] for r in home.find(f"{BOB} rdfs:label ?l", models=[BOB])] == ["Rob"]
    assert [(t.subject, t.predicate, t.object, t.words) for t in told(home, by=BOB)] == [
        (BOB, "rdfs:label", "Rob", "no, it's Rob")]


def test_the_opposite_preference_replaces_a_liking(home: KB) -> None:
    settle(home, Claim(BOB, "likes", "tea", "kind"), Claim(BOB, "likes", "coffee", "kind"))
    settle(home, Claim(BOB, "dislikes", "tea", "kind"))
    assert holds(home, f"{BOB} dislikes dbr:Tea") and not holds(home, f"{BOB} likes dbr:Tea")
    assert holds(home, f"{BOB} likes dbr:Coffee")


def test_provenance_says_who_told_it_when_and_in_what_words(home: KB) -> None:
    settle(home, Claim("mug_red", "belongsTo", BOB), text="the red mug is mine")
    rows = home.find(["?r rdf:subject mug_red", "?r rdf:predicate belongsTo", "?r rdf:object ?o",
                      "?r toldBy ?who", "?r toldAt ?at", "?r toldAs ?words", "?r rdf:type ToldFact"])
    assert [(r["o"], r["who"], r["at"], r["words"]) for r in rows] == [
        (BOB, BOB, "2025-06-01T10:30:00+00:00", "the red mug is mine")]
    # Telling it again refreshes the one record.
    settle(home, Claim("mug_red", "belongsTo", BOB), text="that mug is mine")
    assert [t.words for t in told(home, subject="mug_red")] == ["that mug is mine"]


def test_a_kind_must_be_one_the_kb_knows(home: KB) -> None:
    before = home.size("default", inferred=False)
    settled = settle(home, Claim(BOB, "likes", "jazz", "kind"))
    assert statuses(settled) == ["unknown"] and home.size("default", inferred=False) == before
    # Words that name a thing of the situation and no kind: that thing.
    settled = settle(home, Claim(BOB, "likes", "cookbook", "kind", fallback="book_1"))
    assert statuses(settled) == ["adopted"] and holds(home, f"{BOB} likes book_1")


def test_questions_are_answered_from_the_robots_model_then_from_what_others_said(home: KB) -> None:
    settle(home, Claim("person_alice", "dislikes", "coffee", "kind"))  # believed only (Bob's model)
    settle(home, Claim("person_alice", "likes", "tea", "kind"), speaker="person_alice")
    likes = settle(home, Claim("person_alice", "likes", None)).outcomes[0]
    assert likes.held == (("likes", "dbr:Tea"),) and likes.hearsay == ()
    dislikes = settle(home, Claim("person_alice", "dislikes", None)).outcomes[0]
    assert dislikes.held == () and dislikes.hearsay == ((BOB, "dbr:Coffee"),)


def test_a_statement_is_one_commit_of_the_speakers_model_and_the_robots(home: KB) -> None:
    seen: list[set[str]] = []
    home.on_commit(lambda commit: seen.append({d.model for d in commit.deltas}))
    settle(home, Claim(BOB, "name", "Bob", "text"), Claim("mug_red", "belongsTo", BOB),
           Claim("phone_1", "belongsTo", "person_ines"))
    assert seen == [{BOB, "default"}]
    assert holds(home, f'{BOB} rdfs:label "Bob"', BOB) and holds(home, f'{BOB} rdfs:label "Bob"')


def test_a_refused_write_changes_neither_the_speakers_model_nor_the_robots(home: KB) -> None:
    settle(home, Claim("mug_red", "isOn", "sofa_1"))  # Bob's model exists, with a belief to replace

    def refuse(commit: object) -> None:
        # Only what changes the robot's model: were the belief a commit of its own, it would stay.
        if any(d.model == "default" for d in commit.deltas):  # type: ignore[attr-defined]
            raise KbError("disk full")

    before = {m: sorted(map(str, home.export("nt", m).splitlines())) for m in ("default", BOB)}
    revision = home.revision
    home.on_commit(refuse, durable=True)  # as the journal does when its disk refuses
    for claims in ([Claim(BOB, "name", "Bob", "text")], [Claim("mug_red", "belongsTo", BOB)],
                   [Claim("mug_red", "belongsTo", BOB), Claim("mug_red", "isOn", "table_1")]):
        with pytest.raises(KbError, match="disk full"):
            settle(home, *claims)
    assert {m: sorted(map(str, home.export("nt", m).splitlines())) for m in ("default", BOB)} == before
    assert home.revision == revision and not told(home) and home.models() == ["default", BOB]


def test_what_another_persons_word_made_theirs_is_disputed_under_every_adopting_policy(home: KB) -> None:
    """Issue 26: a claim on what the robot holds as someone else's stays the speaker's belief."""
    settle(home, Claim("mug_red", "belongsTo", "person_alice"), speaker="person_alice")
    for trust in (Trust.PEOPLE, Trust.ALL):
        (outcome,) = settle(home, Claim("mug_red", "belongsTo", BOB), trust=trust).outcomes
        assert (outcome.status, outcome.held, outcome.hearsay) == (
            "disputed", (("belongsTo", "person_alice"),), (("person_alice", "person_alice"),))
    (outcome,) = settle(home, Claim("mug_red", "belongsTo", BOB), speaker="person_ines", trust=Trust.ALL).outcomes
    assert outcome.status == "disputed"  # nor may a third person give it away
    assert holds(home, "mug_red belongsTo person_alice") and holds(home, f"mug_red belongsTo {BOB}", BOB)
    # The owner may; so may whoever told it (their correction).
    settle(home, Claim("keys_1", "belongsTo", "person_ines"), speaker=BOB, trust=Trust.ALL)
    assert statuses(settle(home, Claim("keys_1", "belongsTo", "person_alice"), trust=Trust.ALL)) == ["adopted"]
    assert statuses(settle(home, Claim("mug_red", "belongsTo", "person_ines"), speaker="person_alice",
                           trust=Trust.ALL)) == ["adopted"]
    assert holds(home, "mug_red belongsTo person_ines") and not holds(home, "mug_red belongsTo person_alice")


def test_the_name_of_another_known_person_is_disputed_an_introduction_too(home: KB) -> None:
    for claim in (Claim(BOB, "name", "alice", "text"), Claim("person_x", "name", "Alice", "text"),
                  Claim(BOB, "name", "Ines", "text")):
        (outcome,) = settle(home, claim, trust=Trust.ALL).outcomes
        assert outcome.status == "disputed" and outcome.hearsay[0][0] in ("person_alice", "person_ines")
    assert home.find(f"{BOB} rdfs:label ?l") == [] and home.find("person_x rdfs:label ?l") == []
    assert statuses(settle(home, Claim(BOB, "name", "Alicia", "text"))) == ["adopted"]  # another name
    assert statuses(settle(home, Claim("person_alice", "name", "Alice", "text"), speaker="person_alice")) == [
        "known"]


def test_where_a_thing_is_asked_as_in_is_found_on_too(home: KB) -> None:
    home.update(['diary_1 rdf:type Artifact', 'diary_1 rdfs:label "diary"'])
    settle(home, Claim("diary_1", "isOn", "drawer_1"), speaker="person_alice", trust=Trust.NONE)
    where = settle(home, Claim("diary_1", "isIn", None)).outcomes[0]
    assert (where.claim.predicate, where.held, where.hearsay) == ("isOn", (), (("person_alice", "drawer_1"),))
    nowhere = settle(home, Claim("keys_1", "isOn", None)).outcomes[0]  # the robot's isIn holds it
    assert nowhere.held == (("isIn", "kitchen"),)
