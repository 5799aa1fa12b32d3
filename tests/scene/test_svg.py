"""The simulator's SVG environment format: layers, labels, units, transforms, errors."""

from __future__ import annotations

from importlib.resources import files

import pytest

from kb.errors import KbError
from scene.scene import Kind
from scene.svg import load_svg

HEAD = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
        'viewBox="0 0 5000 3000">')


def svg(body: str) -> str:
    return HEAD + body + "</svg>"


def test_demo_environment() -> None:
    entities = {e.id: e for e in load_svg((files("ontologies") / "demo.svg").read_bytes())}
    assert {"living_room", "kitchen", "bedroom", "table", "sofa", "shelf", "cup", "apple", "book",
            "person_alice"} <= set(entities)
    assert entities["table"].cls == "dbr:Table_(furniture)" and entities["table"].kind is Kind.FURNITURE
    assert entities["kitchen"].kind is Kind.ZONE and entities["kitchen"].cls == "ZoneOfInterest"
    assert entities["living_room"].label == "living room"
    assert entities["person_alice"].kind is Kind.PERSON and entities["person_alice"].label == "Alice"
    # The table's group is translated to (2000, 2500): 2 m ahead of the robot, on its axis.
    assert (entities["table"].x, entities["table"].y) == (pytest.approx(2.0), pytest.approx(0.0))
    assert (entities["table"].width, entities["table"].depth) == (pytest.approx(1.2), pytest.approx(0.8))


def test_layers_labels_and_captions() -> None:
    entities = load_svg(svg(
        '<g inkscape:label="zones"><rect inkscape:label="hall dbr:Ignored" x="0" y="0" width="1000" height="3000"/>'
        '<text inkscape:label="_label1" x="0" y="0">hall</text></g>'
        '<g inkscape:label="walls"><rect inkscape:label="wall1" x="0" y="0" width="10" height="10"/></g>'
        '<g inkscape:label="dynamic_objects"><rect inkscape:label="ghost dbr:Cup" width="10" height="10"/></g>'
        '<g inkscape:label="static_objects"><rect inkscape:label="crate" x="1000" y="1400" width="200" height="200"/>'
        '<g inkscape:label="inner"><rect inkscape:label="nested dbr:Cup" width="10" height="10"/></g></g>'
    ))
    by_id = {e.id: e for e in entities}
    assert set(by_id) == {"hall", "crate", "inner"}  # only direct children, walls and other layers ignored
    assert by_id["hall"].cls == "ZoneOfInterest"  # a zone's class token is ignored
    assert by_id["crate"].cls == "Object"  # oro:Object when no class is given
    assert (by_id["crate"].x, by_id["crate"].y) == (pytest.approx(1.1), pytest.approx(0.0))


def test_millimetres_and_robot_frame() -> None:
    (item,) = load_svg(svg('<g inkscape:label="static_objects">'
                           '<rect inkscape:label="box_1" x="2900" y="400" width="200" height="200"/></g>'))
    # SVG "up" is the robot's left: y = (H/2 - cy) / 1000.
    assert (item.x, item.y, item.width) == (pytest.approx(3.0), pytest.approx(1.0), pytest.approx(0.2))


def test_nested_and_rotated_transforms() -> None:
    (item,) = load_svg(svg(
        '<g inkscape:label="static_objects" transform="translate(1000,0)">'
        '<g inkscape:label="bench dbr:Couch" transform="translate(1000,1500) rotate(90)">'
        '<rect x="-500" y="-100" width="1000" height="200"/></g></g>'
    ))
    assert (item.x, item.y) == (pytest.approx(2.0), pytest.approx(0.0))
    assert (item.width, item.depth) == (pytest.approx(0.2), pytest.approx(1.0))


def test_path_geometry() -> None:
    (item,) = load_svg(svg('<g inkscape:label="static_objects">'
                           '<path inkscape:label="rug" d="m 1000,1000 h 500 v 1000 h -500 z"/></g>'))
    assert (item.width, item.depth) == (pytest.approx(0.5), pytest.approx(1.0))


@pytest.mark.parametrize(
    ("document", "message"),
    [
        ("<svg><g>", "malformed SVG"),
        ('<html xmlns="http://www.w3.org/1999/xhtml"/>', "not an SVG document"),
        (svg('<g inkscape:label="static_objects"><rect inkscape:label="lamp foo:Lamp" width="1" height="1"/></g>'),
         "lamp foo:Lamp"),
        (svg('<g inkscape:label="static_objects"><rect inkscape:label="b@d dbr:Cup" width="1" height="1"/></g>'),
         "b@d"),
        (svg('<g inkscape:label="static_objects"><path inkscape:label="p" d="10 10"/></g>'), "malformed path"),
        ('<svg xmlns="http://www.w3.org/2000/svg" height="30cm"/>', "no viewBox"),
    ],
)
def test_bad_documents_name_the_problem(document: str, message: str) -> None:
    with pytest.raises(KbError, match=message):
        load_svg(document)


def test_entity_bombs_are_refused() -> None:
    bomb = '<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaa">]><svg xmlns="http://www.w3.org/2000/svg">&a;</svg>'
    with pytest.raises(KbError, match="malformed SVG"):
        load_svg(bomb)
