"""The maintained snapshot (and lexicon) equals a from-scratch build after any sequence of commits."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dialogue.reference.grounding import Entity, Grounder, Snapshot, build_snapshot
from dialogue.reference.lexicon import Lexicon
from dialogue.reference.lexicons import LexiconCache
from kb import KB
from tests.dialogue.conftest import english

BASE = [
    "myself rdf:type Robot", "kitchen rdf:type ZoneOfInterest", 'kitchen rdfs:label "kitchen"',
    "hall rdf:type ZoneOfInterest", "table_1 rdf:type dbr:Table_(furniture)", "table_1 isIn kitchen",
    "person_ann rdf:type Human", 'person_ann rdfs:label "Ann"',
]  # fmt: skip
SUBJECTS = ["thing_0", "thing_1", "thing_2", "thing_3", "person_bo", "table_1", "kitchen", "hall", "myself", "red"]
OBJECTS = ["thing_0", "thing_1", "table_1", "kitchen", "hall", "red", "grey", "person_ann", "person_bo"]
CLASSES = ["dbr:Cup", "dbr:Book", "dbr:Apple", "Remote", "Human", "ZoneOfInterest", "dbr:Table_(furniture)"]
# Synonyms ("fridge" = "refrigerator", "grey" = "gray") and a closed compound ("teacup") among them.
LABELS = ['"red thing"', '"old cup"', '"Bo"', '"rouge"@fr', '"mug"@en', '"kitchen fridge"', '"teacup"']
PROPERTIES = ["isOn", "isIn", "hasColor", "belongsTo", "looksAt", "holds"]

statement = st.one_of(
    st.builds("{} rdf:type {}".format, st.sampled_from(SUBJECTS), st.sampled_from(CLASSES)),
    st.builds("{} rdfs:label {}".format, st.sampled_from([*SUBJECTS, "dbr:Cup", "Remote"]), st.sampled_from(LABELS)),
    st.builds("{} {} {}".format, st.sampled_from(SUBJECTS), st.sampled_from(PROPERTIES), st.sampled_from(OBJECTS)),
    st.builds("myself sees {}".format, st.sampled_from(OBJECTS)),
    st.builds("{} engagementLevel {}".format, st.sampled_from(["person_ann", "person_bo"]),
              st.sampled_from(["engaged", "disengaged"])),
    st.builds("{} isMovable {}".format, st.sampled_from(SUBJECTS), st.sampled_from(["true", "false"])),
    st.just("dbr:Mug rdfs:subClassOf dbr:Cup"),  # a TBox change: the full rebuild path
    st.just("thing_2 rdf:type dbr:Mug"),
)
commit = st.tuples(
    st.sampled_from(["update", "remove", "apply", "clear"]),
    st.lists(statement, min_size=1, max_size=6),
    st.lists(statement, max_size=4),
).filter(lambda c: c[0] != "clear" or not c[2])


def _assert_contents(snapshot: Snapshot) -> None:
    """`contents` holds, for each place, exactly the entities on it or in it (support, zone, the
    other places it is in), and `placed_at` gives them in the snapshot's order (as looking at every
    entity would)."""

    def at(e: Entity) -> set[str]:
        return {p for p in (e.support, e.zone) if p is not None} | {o for r, o in e.relations if r == "in"}

    places = {p for e in snapshot.entities.values() for p in at(e)}
    assert snapshot.contents is not None
    assert set(snapshot.contents) == places
    for place in places:
        everyone = [e for e in snapshot.entities.values() if place in at(e)]
        assert set(snapshot.contents[place]) == {e.id for e in everyone}
        assert snapshot.placed_at(place) == everyone
    assert snapshot.placed_at("nowhere") == []


def _lexicon_state(lex: Lexicon) -> tuple[object, ...]:
    """What a lexicon answers: every entity's qualifiers, the names of every indexed words, the name
    lengths by first word, the entities by label word and the vocabulary with its counts."""
    named = {w: lex._named(w) for w in {*lex._by_words, *lex._kind_words}}
    return (
        {e: frozenset(words) for e, words in lex.attributes.items()},
        {w: sorted((n.words, n.entity, n.source) for n in names) for w, names in named.items() if names},
        dict(lex._lengths),
        {w: sorted(ids) for w, ids in lex.by_label_word.items()},
        dict(lex.vocabulary),
    )


@settings(max_examples=60, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(commit, min_size=1, max_size=8))
def test_maintained_snapshot_and_lexicon_equal_a_full_build(commits: list[tuple[str, list[str], list[str]]]) -> None:
    kb = KB()
    kb.update(BASE)
    grounder, lexicons = Grounder(), LexiconCache(english())
    lexicons.get(grounder.snapshot(kb))
    for action, first, second in commits:
        if action == "update":
            kb.update(first)
        elif action == "remove":
            kb.remove(first)
        elif action == "apply":
            kb.apply(add=first, remove=second)
        else:
            kb.clear()
            kb.update(BASE[: len(first)])
        maintained = grounder.snapshot(kb)
        fresh = build_snapshot(kb)
        assert maintained == fresh
        assert list(maintained.entities) == list(fresh.entities)  # the same deterministic order
        _assert_contents(maintained)
        assert _lexicon_state(lexicons.get(maintained)) == _lexicon_state(Lexicon(fresh, english()))


def test_a_commit_updates_only_what_it_touched() -> None:
    kb = KB()
    kb.update([*BASE, *(f"thing_{i} isIn kitchen" for i in range(50)), *(f"thing_{i} rdf:type dbr:Cup"
                                                                         for i in range(50))])
    grounder = Grounder()
    grounder.snapshot(kb)
    kb.apply(add=["thing_3 isIn hall", "myself sees thing_4"], remove=["thing_3 isIn kitchen"])
    snap = grounder.snapshot(kb)
    assert snap.changed_since(snap.changed[-1][0]) == {"thing_3", "thing_4"}
    assert snap.entities["thing_3"].zone == "hall" and snap.entities["thing_4"].seen


def test_a_class_label_renames_its_instances() -> None:
    kb = KB()
    kb.update([*BASE, "cup_1 rdf:type Beaker", "cup_1 isIn kitchen"])
    grounder = Grounder()
    assert grounder.snapshot(kb).entities["cup_1"].name == "beaker"
    kb.update(['Beaker rdfs:label "tumbler"'])
    assert grounder.snapshot(kb).entities["cup_1"].name == "tumbler"


def test_asserting_a_type_that_was_only_inferred_is_seen() -> None:
    # "thing_2 rdf:type dbr:Cup" when it is already a cup as a mug changes no fact of the closure,
    # but which classes are its own, and so its name (found by the property test)
    kb = KB()
    kb.update([*BASE, "dbr:Mug rdfs:subClassOf dbr:Cup", "thing_2 isOn thing_0", "thing_2 rdf:type dbr:Mug"])
    grounder = Grounder()
    grounder.snapshot(kb)
    kb.update(["thing_2 rdf:type dbr:Cup"])
    assert grounder.snapshot(kb) == build_snapshot(kb)
    kb.remove(["thing_2 rdf:type dbr:Cup"])
    assert grounder.snapshot(kb) == build_snapshot(kb)


def test_a_colour_label_renames_the_colour_of_its_things() -> None:
    kb = KB()
    kb.update([*BASE, "cup_1 rdf:type dbr:Cup", "cup_1 isIn kitchen", "cup_1 hasColor teal_shade"])
    grounder = Grounder()
    assert grounder.snapshot(kb).entities["cup_1"].colour == "teal shade"
    kb.update(['teal_shade rdfs:label "teal"'])
    assert grounder.snapshot(kb).entities["cup_1"].colour == "teal"
    assert grounder.snapshot(kb) == build_snapshot(kb)


def test_a_lexicon_that_missed_snapshots_catches_up_from_their_steps() -> None:
    kb = KB()
    kb.update(BASE)
    grounder = Grounder()
    first = Lexicon(grounder.snapshot(kb), english())
    kb.update(["cup_1 rdf:type dbr:Cup", "cup_1 isIn kitchen"])
    grounder.snapshot(kb)  # a snapshot this lexicon never sees
    kb.update(['cup_1 rdfs:label "blue mug"', "myself sees cup_1"])
    latest = grounder.snapshot(kb)
    assert latest.changed_since(first.snapshot.revision) == {"cup_1"}
    caught_up = Lexicon(latest, english(), first)
    assert caught_up._entries["kitchen"] is first._entries["kitchen"]  # updated from the steps, not rebuilt
    assert _lexicon_state(caught_up) == _lexicon_state(Lexicon(build_snapshot(kb), english()))


def test_an_updated_lexicon_knows_the_new_words_and_forgets_the_old() -> None:
    kb = KB()
    kb.update([*BASE, "cup_1 rdf:type Artifact", 'cup_1 rdfs:label "teacup"', "cup_1 isIn kitchen"])
    grounder, lexicons = Grounder(), LexiconCache(english())
    first = lexicons.get(grounder.snapshot(kb))
    assert first.knows("teacup") and not first.knows("refrigerator")
    kb.apply(add=['cup_1 rdfs:label "kitchen fridge"'], remove=['cup_1 rdfs:label "teacup"'])
    snapshot = grounder.snapshot(kb)
    assert snapshot.changed_since(first.snapshot.revision) == {"cup_1"}  # the update path, not a rebuild
    lex = lexicons.get(snapshot)
    assert lex.knows("fridges") and lex.knows("refrigerator") and not lex.knows("teacup")
    assert {n.entity for n in lex.names_at(["refrigerator"], 0)} == {"cup_1"}
    assert lex.names_at(["tea", "cup"], 0) == [] and "kitchen" in lex.by_label_word
    kb.apply(add=['cup_1 rdfs:label "teacup"'], remove=['cup_1 rdfs:label "kitchen fridge"'])
    lex = lexicons.get(grounder.snapshot(kb))
    assert [(n.entity, n.words) for n in lex.names_at(["tea", "cups"], 0)] == [("cup_1", ("tea", "cups"))]
    assert not lex.knows("fridge") and lex.knows("kitchen")  # still the zone's name


def test_what_each_place_holds_follows_moves_and_removals() -> None:
    kb = KB()
    kb.update([*BASE, "cup_1 rdf:type dbr:Cup", "cup_1 isOn table_1", "cup_1 isIn kitchen",
               "book_1 rdf:type dbr:Book", "book_1 isIn kitchen"])
    grounder = Grounder()
    first = grounder.snapshot(kb)
    assert [e.id for e in first.placed_at("kitchen")] == ["book_1", "cup_1", "table_1"]
    kb.apply(add=["cup_1 isIn hall"], remove=["cup_1 isIn kitchen", "cup_1 isOn table_1"])
    moved = grounder.snapshot(kb)
    assert [e.id for e in moved.placed_at("kitchen")] == ["book_1", "table_1"]
    assert [e.id for e in moved.placed_at("hall")] == ["cup_1"] and moved.placed_at("table_1") == []
    kb.remove(["book_1 isIn kitchen"])  # no longer placed, nor seen: no longer an entity
    gone = grounder.snapshot(kb)
    assert [e.id for e in gone.placed_at("kitchen")] == ["table_1"]
    _assert_contents(gone)
    assert [e.id for e in first.placed_at("kitchen")] == ["book_1", "cup_1", "table_1"]  # immutable


def test_a_named_thing_nobody_has_placed_is_an_entity_and_the_ontologys_values_are_not() -> None:
    kb = KB()
    kb.update([*BASE, "diary_1 rdf:type Artifact"])
    grounder = Grounder()
    assert "diary_1" not in grounder.snapshot(kb).entities  # typed, unnamed, unplaced: nothing to say
    kb.update(['diary_1 rdfs:label "diary"'])
    diary = grounder.snapshot(kb).entities["diary_1"]
    assert (diary.name, diary.kind, diary.support, diary.zone, diary.seen) == ("diary", "thing", None, None, False)
    assert {n.entity for n in Lexicon(grounder.snapshot(kb), english()).names_at(["diary"], 0)} == {"diary_1"}
    kb.remove(['diary_1 rdfs:label "diary"'])
    assert "diary_1" not in grounder.snapshot(kb).entities
    # Colours, sizes, postures, engagement levels and the unknown location are named by the
    # ontology: values, never things.
    values = {"red", "large", "sitting", "engaged", "unknownLocation", "current_world_state"}
    assert not values & set(build_snapshot(kb).entities)


def test_a_persons_family_is_kept_either_way_round_as_commits_change_it() -> None:
    kb = KB()
    kb.update([*BASE, "person_bo rdf:type Human", 'person_bo rdfs:label "Bo"', "person_ann isParentOf person_bo"])
    grounder = Grounder()
    snap = grounder.snapshot(kb)
    assert snap.entities["person_ann"].kin == (("child", "person_bo"),)
    assert snap.entities["person_bo"].kin == (("parent", "person_ann"),)  # (no property of Bo's says it)
    kb.apply(add=["person_bo hasSpouse person_ann"], remove=["person_ann isParentOf person_bo"])
    snap = grounder.snapshot(kb)
    assert snap.entities["person_ann"].kin == (("spouse", "person_bo"),)
    assert snap.entities["person_bo"].kin == (("spouse", "person_ann"),)
    assert build_snapshot(kb).entities["person_ann"] == snap.entities["person_ann"]
    assert snap.entities["table_1"].kin == ()
