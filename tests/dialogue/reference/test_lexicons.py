from dialogue.reference.grounding import build_snapshot
from dialogue.reference.lexicons import LexiconCache
from kb import KB
from tests.dialogue.conftest import english


def test_unchanged_entities_are_reused_across_revisions(office: KB) -> None:
    cache = LexiconCache(english())
    first = cache.get(build_snapshot(office))
    office.update(["laptop_1 hasColor black"])
    second = cache.get(build_snapshot(office))
    assert second is not first and "black" in second.attributes["laptop_1"]
    assert second._entries["stapler_1"][1] is first._entries["stapler_1"][1]  # its names not made again
