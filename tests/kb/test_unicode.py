"""Text that is not valid Unicode (a lone surrogate) is refused by the KB itself, whatever way it
comes in, with a KbError naming the problem, and nothing is written (issue 19, item 7)."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest

from kb import KB, KbError
from kb.errors import InvalidUnicode
from kb.unicode import check_text
from scene.scene import Entity, Kind
from scene.sync import entity_from_json, scene_from_json

LONE = "\ud800"


@pytest.fixture
def kb() -> Iterator[KB]:
    with KB(ontology=False) as k:
        k += ["cup_1 isOn table_1"]
        yield k


WRITES: dict[str, Callable[[KB], object]] = {
    "add, surrogate in a literal": lambda kb: kb.add(f'cup_1 rdfs:label "{LONE}"'),
    "add, N3 escape of one": lambda kb: kb.add('cup_1 rdfs:label "\\ud800"'),
    "add, low surrogate escape": lambda kb: kb.add('cup_1 rdfs:label "a\\uDC00b"@en'),
    "add, in a datatype IRI": lambda kb: kb.add(f'cup_1 weight "1"^^<http://x.org/{LONE}>'),
    "add, in a name": lambda kb: kb.add(f"cup_1 isOn <http://x.org/{LONE}>"),
    "update": lambda kb: kb.update([f'cup_1 rdfs:label "{LONE}"']),
    "apply": lambda kb: kb.apply([f'cup_1 rdfs:label "ok{LONE}"'], ["cup_1 isOn table_1"]),
    "revise": lambda kb: kb.revise([f'cup_1 rdfs:label "{LONE}"'], {"method": "add"}),
    "remove with a pattern": lambda kb: kb.remove([f'?x rdfs:label "{LONE}"']),
    "load_data turtle escape": lambda kb: kb.load_data('<http://x.org/a> <http://x.org/b> "\\ud800" .', "turtle"),
    "load_data n-triples escape": lambda kb: kb.load_data('<http://x.org/a> <http://x.org/b> "\\uDFFF" .', "nt"),
    "load_data json-ld escape": lambda kb: kb.load_data(
        '{"@id": "http://x.org/a", "http://x.org/b": "\\ud800"}', "json-ld"),
    "sparql_update escape": lambda kb: kb.sparql_update(
        'INSERT DATA { <http://x.org/a> <http://x.org/b> "\\ud800" }'),
}
READS: dict[str, Callable[[KB], object]] = {
    "find": lambda kb: kb.find([f'?x rdfs:label "{LONE}"']),
    "sparql escape": lambda kb: kb.sparql('SELECT ?x WHERE { BIND("\\ud800" AS ?x) }'),
    "sparql raw": lambda kb: kb.sparql(f'SELECT ?x WHERE {{ BIND("{LONE}" AS ?x) }}'),
    "subscribe": lambda kb: kb.subscribe([f'?x rdfs:label "{LONE}"'], lambda rows: None),
}


@pytest.mark.parametrize("write", list(WRITES), ids=list(WRITES))
def test_a_write_holding_a_lone_surrogate_is_refused_and_changes_nothing(kb: KB, write: str) -> None:
    before = (kb.revision, kb.export("nt"))
    with pytest.raises(KbError, match=r"not valid Unicode.*lone surrogate U\+D[89A-F]"):
        WRITES[write](kb)
    assert (kb.revision, kb.export("nt")) == before
    kb.export("json-ld").decode("utf-8")  # every answer stays encodable


@pytest.mark.parametrize("read", list(READS), ids=list(READS))
def test_a_query_holding_a_lone_surrogate_is_refused(kb: KB, read: str) -> None:
    with pytest.raises(KbError, match="not valid Unicode"):
        READS[read](kb)


def test_valid_text_beyond_the_bmp_is_accepted(kb: KB) -> None:
    kb.add(['cup_1 rdfs:label "tasse \U0001F375"@fr', 'cup_1 comment "\\U0001F375 \\u00e9"'])
    assert kb["cup_1 rdfs:label ?l"] == [{"l": "tasse \U0001F375"}]
    assert kb["cup_1 comment ?c"] == [{"c": "\U0001F375 é"}]


def test_scene_entities_with_a_lone_surrogate_are_refused() -> None:
    with pytest.raises(InvalidUnicode, match="the label of scene entity 'cup_1'"):
        Entity("cup_1", Kind.OBJECT, label=f"red {LONE}")
    with pytest.raises(KbError, match="not valid Unicode"):
        entity_from_json({"id": f"cup{LONE}", "x": 1, "y": 0})
    with pytest.raises(KbError, match="the class of scene entity"):
        scene_from_json('{"entities": [{"id": "cup_1", "class": "dbr:Cup\\udc00", "x": 1, "y": 0}]}')


def test_check_text_names_the_place() -> None:
    check_text("fine \U0001F375", "x")
    with pytest.raises(InvalidUnicode, match=r"the input is not valid Unicode: it holds the lone surrogate "
                                             r"U\+DC00 at character 2"):
        check_text("ab\udc00", "the input")
