"""``kb.records``: journal statements read back to the very triples written, by the fast path for
names and blank nodes as by the tokenizer, and corrupt ones refused."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st
from rdflib import BNode, Literal, URIRef

from kb.errors import KbError
from kb.records import nt, parse_nt
from kb.terms import Triple

_names = st.sampled_from(["http://kb.openrobots.org#cup_1", "http://ex.org/a(b)", "urn:x:é",
                          "https://dbpedia.org/resource/Table_(furniture)"]).map(URIRef)
_objects = st.one_of(_names, st.sampled_from(["b1", "n0abc"]).map(BNode),
                     st.text(st.characters(exclude_categories=("Cs",)), max_size=8).map(Literal),
                     st.integers().map(Literal))


@given(st.tuples(st.one_of(_names, st.sampled_from(["b1"]).map(BNode)), _names, _objects))
def test_a_written_statement_reads_back_the_same(triple: Triple) -> None:
    bnodes: dict[str, BNode] = {}
    assert parse_nt(nt(triple), bnodes) == triple


def test_the_fast_path_gives_what_the_tokenizer_gives() -> None:
    from kb.records import _node
    from kb.terms import tokenize

    for statement in ["<http://ex.org/a> <http://ex.org/p> <http://ex.org/b>",
                      "_:x <http://ex.org/p> _:y", "<http://ex.org/a>\t<http://ex.org/p>  <urn:x>"]:
        fast = parse_nt(statement, {})
        slow = tuple(_node(token, {}) for token in tokenize(statement))
        assert fast == slow


@pytest.mark.parametrize("statement", [
    "<http://ex.org/a> <http://ex.org/p>",
    "<http://ex.org/a> <http://ex.org/p> <http://ex.org/b> <http://ex.org/c>",
    "<http://ex.org/a>x <http://ex.org/p> <http://ex.org/b>",
    "<not an iri> <http://ex.org/p> <http://ex.org/b>",
    "<relative> <http://ex.org/p> <http://ex.org/b>",
])
def test_corrupt_statements_are_refused(statement: str) -> None:
    with pytest.raises(KbError):
        parse_nt(statement, {})


# --- the scan: a record cut short is a torn tail; any other bad record is damage (issue 26, item 6)

def _journal(count: int) -> bytes:
    from kb.records import frame

    return b"".join(frame({"revision": n, "changes": [{"model": "default", "add": [
        f"<http://kb.openrobots.org#s{n}> <http://kb.openrobots.org#sees> \"caf\u00e9 {n}\""],
        "remove": []}]}) for n in range(1, count + 1))


def test_every_flipped_bit_of_the_last_record_is_damage_never_a_torn_tail() -> None:
    from kb.records import scan

    data = _journal(3)
    last = data.rindex(b"\n", 0, len(data) - 1) + 1
    for at in range(last, len(data)):
        for bit in range(8):
            flipped = bytearray(data)
            flipped[at] ^= 1 << bit
            found = scan(bytes(flipped))
            revisions = [r["revision"] for _s, _e, r in found.records]
            assert found.torn_bytes == 0, (at, bit)
            # damage, unless the flip left the record whole (the case of a hex digit of its checksum)
            assert (found.damage and revisions == [1, 2]) or (not found.damage and revisions == [1, 2, 3]), \
                (at, bit)


def test_every_cut_of_the_last_record_is_a_torn_tail() -> None:
    from kb.records import scan

    data = _journal(3)
    last = data.rindex(b"\n", 0, len(data) - 1) + 1
    for end in range(last + 1, len(data) - 1):  # at least one byte, not the whole record
        found = scan(data[:end])
        assert not found.damage and found.torn_at == last, end
        assert [r["revision"] for _s, _e, r in found.records] == [1, 2]
    # zeros a crash allocated past the cut are part of the torn tail
    found = scan(data[: last + 10] + b"\0" * 30)
    assert not found.damage and found.torn_at == last


def test_a_last_record_that_only_lacks_its_newline_is_whole() -> None:
    from kb.records import scan

    data = _journal(3)
    found = scan(data[:-1])
    assert not found.damage and found.torn_bytes == 0 and found.unterminated
    assert [r["revision"] for _s, _e, r in found.records] == [1, 2, 3]


@pytest.mark.parametrize(("snapshot", "revisions", "missing"), [
    (0, [1, 2, 3], None), (0, [], None), (5, [], None), (5, [6, 7], None),
    (5, [3, 4, 5, 6], None),  # records the snapshot holds, left by a journal not emptied
    (5, [3, 4, 5], None), (0, [51, 52], range(1, 51)), (5, [9, 10], range(6, 9)),
])
def test_a_journal_must_continue_its_snapshot(snapshot: int, revisions: list[int], missing: range | None) -> None:
    from kb.records import missing_revisions

    assert missing_revisions(snapshot, revisions) == missing
