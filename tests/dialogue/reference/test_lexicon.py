from dialogue.reference.grounding import build_snapshot
from dialogue.reference.lexicon import Lexicon, LexiconCache, singular, tokens
from kb import KB


def test_tokens_and_singular() -> None:
    assert tokens("Don't grab cup_1, OK?") == ["don't", "grab", "cup", "1", "ok"]
    assert [singular(w) for w in ("cups", "glasses", "boxes", "berries", "glass", "is")] == [
        "cup", "glass", "box", "berry", "glass", "is",
    ]  # fmt: skip


def test_names_come_from_labels_ids_classes_and_heads(office: KB) -> None:
    lex = Lexicon(build_snapshot(office))
    mug = {n.words for n in lex.names_at(["green", "mug"], 0)}
    assert ("green", "mug") in mug
    assert {n.entity for n in lex.names_at(["mug"], 0)} == {"mug_green", "mug_yellow"}  # head noun
    assert {n.entity for n in lex.names_at(["cup"], 0)} == {"mug_green", "mug_yellow"}  # class label
    assert {n.entity for n in lex.names_at(["stapler", "1"], 0)} == {"stapler_1"}  # id
    assert "green" in lex.attributes["mug_green"] and "gray" in lex.attributes["laptop_1"]


def test_mentions_are_longest_first(office: KB) -> None:
    lex = Lexicon(build_snapshot(office))
    mentions = lex.mentions(tokens("the yellow mug is on the desk"))
    assert [(m.start, m.end, set(m.entities)) for m in mentions] == [
        (1, 3, {"mug_yellow"}), (6, 7, {"desk_1"}),
    ]  # fmt: skip


def test_unchanged_entities_are_reused_across_revisions(office: KB) -> None:
    cache = LexiconCache()
    first = cache.get(build_snapshot(office))
    office.update(["laptop_1 hasColor black"])
    second = cache.get(build_snapshot(office))
    assert second is not first and "black" in second.attributes["laptop_1"]
    assert second.attributes["stapler_1"] is first.attributes["stapler_1"]
