"""The interaction simulator's SVG environment format (scene-compat §2) to scene entities.

Groups labelled ``static_objects`` (furniture), ``zones`` and ``walls`` (ignored: not semantic)
are read, their direct children labelled ``name [class CURIE]`` become entities; labels starting
with ``_`` are captions. One user unit is one millimetre; the robot stands at (0, H/2) facing +x.
situated also reads a ``people`` layer (ignored by the simulator) whose children are persons:
``person_id [class]`` with optional ``data-label`` (a display name) and ``data-heading-deg``
(the direction the person faces, degrees counter-clockwise from the robot's +x).
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from xml.etree.ElementTree import Element, ParseError

from defusedxml import DefusedXmlException
from defusedxml.ElementTree import fromstring

from kb.errors import KbError
from kb.terms import parse_name
from scene.scene import Entity, Kind

SVG = "{http://www.w3.org/2000/svg}"
INKSCAPE_LABEL = "{http://www.inkscape.org/namespaces/inkscape}label"
LAYERS = {"static_objects": Kind.FURNITURE, "zones": Kind.ZONE, "people": Kind.PERSON}
Matrix = tuple[float, float, float, float, float, float]
IDENTITY: Matrix = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)
Point = tuple[float, float]

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_TRANSFORM = re.compile(r"(matrix|translate|scale|rotate|skewX|skewY)\s*\(([^)]*)\)")
_PATH_TOKEN = re.compile(rf"[MmLlHhVvCcSsQqTtAaZz]|{_NUMBER}")
_NUM = re.compile(_NUMBER)
_ARITY = {"M": 2, "L": 2, "H": 1, "V": 1, "C": 6, "S": 4, "Q": 4, "T": 2, "A": 7, "Z": 0}


def load_svg(data: str | bytes) -> list[Entity]:
    """Entities of an SVG environment, in document order (later ones stack above)."""
    try:
        root = fromstring(data)
    except (ParseError, DefusedXmlException) as exc:
        raise KbError(f"malformed SVG: {exc}") from exc
    if root.tag != f"{SVG}svg":
        raise KbError(f"not an SVG document: the root element is <{_local(root.tag)}>")
    half_height = _document_height(root) / 2
    layers: dict[str, tuple[Element, Matrix]] = {}
    for group, matrix in _groups(root, IDENTITY):
        label = group.get(INKSCAPE_LABEL, "")
        if label in LAYERS or label == "walls":
            layers[label] = (group, matrix)  # with several groups of one label the last wins
    entities: list[Entity] = []
    for name, kind in LAYERS.items():
        if name not in layers:
            continue
        group, outer = layers[name]
        matrix = _compose(outer, _transform(group))
        for child in group:
            label = (child.get(INKSCAPE_LABEL) or "").strip()
            if not label or label.startswith("_"):
                continue
            entities.append(_entity(child, label, kind, _compose(matrix, _transform(child)), half_height))
    return entities


def _entity(element: Element, label: str, kind: Kind, matrix: Matrix, half_height: float) -> Entity:
    where = f"<{_local(element.tag)} id={element.get('id')!r} label={label!r}>"
    tokens = label.split(" ")
    entity_id = tokens[0]
    try:
        parse_name(entity_id, f"the name of {where}")
        cls = tokens[1] if len(tokens) > 1 and tokens[1] else ""
        if cls:
            parse_name(cls, f"the class of {where}")
    except KbError as exc:
        raise KbError(f"SVG element {where}: {exc}") from None
    if kind is Kind.ZONE:
        cls = ""  # every zone is a ZoneOfInterest (§2.3)
    points = list(_points(element, matrix))
    if not points:
        raise KbError(f"SVG element {where} has no geometry")
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
    heading = math.radians(_float(element.get("data-heading-deg", "0"), where))
    sized = kind is not Kind.PERSON  # people keep the simulator's fixed 0.3 m
    return Entity(
        id=entity_id, kind=kind, cls=cls, label=element.get("data-label"),
        x=cx / 1000, y=(half_height - cy) / 1000, heading=heading,
        width=(max(xs) - min(xs)) / 1000 if sized else None,
        depth=(max(ys) - min(ys)) / 1000 if sized else None,
    )


def _document_height(root: Element) -> float:
    view_box = root.get("viewBox")
    if view_box:
        values = _NUM.findall(view_box)
        if len(values) == 4:
            return float(values[3])
        raise KbError(f"malformed SVG viewBox {view_box!r}: expected four numbers")
    height = root.get("height", "")
    if _NUM.fullmatch(height.strip()):
        return float(height)
    raise KbError("the SVG has no viewBox and no unitless height: the robot's place (0, H/2) is unknown")


def _groups(element: Element, matrix: Matrix) -> Iterator[tuple[Element, Matrix]]:
    """Every <g> with the transform of its ancestors (not its own)."""
    for child in element:
        if child.tag == f"{SVG}g":
            yield child, matrix
            yield from _groups(child, _compose(matrix, _transform(child)))


def _points(element: Element, matrix: Matrix) -> Iterator[Point]:
    """Points whose bounding box is the element's (curve control points over-approximate)."""
    tag, where = _local(element.tag), f"<{_local(element.tag)} id={element.get('id')!r}>"

    def num(name: str, default: str = "0") -> float:
        return _float(element.get(name, default), f"attribute {name} of {where}")

    local: list[Point] = []
    if tag in ("rect", "image", "use") and element.get("width") is not None:
        x, y, w, h = num("x"), num("y"), num("width"), num("height")
        local = [(x, y), (x + w, y), (x + w, y + h), (x, y + h)]
    elif tag in ("circle", "ellipse"):
        cx, cy = num("cx"), num("cy")
        rx = num("r") if tag == "circle" else num("rx")
        ry = num("r") if tag == "circle" else num("ry")
        local = [(cx - rx, cy - ry), (cx + rx, cy - ry), (cx + rx, cy + ry), (cx - rx, cy + ry)]
    elif tag == "line":
        local = [(num("x1"), num("y1")), (num("x2"), num("y2"))]
    elif tag in ("polyline", "polygon"):
        values = [float(v) for v in _NUM.findall(element.get("points", ""))]
        local = list(zip(values[0::2], values[1::2], strict=False))
    elif tag == "path":
        local = _path_points(element.get("d", ""), where)
    elif tag in ("g", "a", "switch"):
        for child in element:
            yield from _points(child, _compose(matrix, _transform(child)))
        return
    for x, y in local:
        yield _apply(matrix, x, y)


def _path_points(d: str, where: str) -> list[Point]:
    points: list[Point] = []
    x = y = start_x = start_y = 0.0
    command = ""
    tokens = _PATH_TOKEN.findall(d)
    i = 0
    while i < len(tokens):
        if tokens[i].isalpha():
            command = tokens[i]
            i += 1
            if command in "Zz":
                x, y = start_x, start_y
                continue
        if not command:
            raise KbError(f"malformed path data in {where}: it does not start with a command")
        upper = command.upper()
        arity = _ARITY[upper]
        args = tokens[i : i + arity]
        if len(args) < arity or any(a.isalpha() for a in args):
            raise KbError(f"malformed path data in {where}: {command} needs {arity} numbers")
        values = [float(a) for a in args]
        i += arity
        relative = command.islower()
        if upper == "H":
            x = values[0] + (x if relative else 0)
        elif upper == "V":
            y = values[0] + (y if relative else 0)
        elif upper == "A":
            x, y = values[5] + (x if relative else 0), values[6] + (y if relative else 0)
        else:
            pairs = list(zip(values[0::2], values[1::2], strict=True))
            for px, py in pairs:
                points.append((px + x, py + y) if relative else (px, py))
            x, y = points[-1]
        if upper == "M":
            start_x, start_y = x, y
            command = "l" if relative else "L"  # further pairs after a moveto are linetos
        points.append((x, y))
    return points


def _transform(element: Element) -> Matrix:
    text = element.get("transform")
    if not text:
        return IDENTITY
    matrix = IDENTITY
    for name, raw in _TRANSFORM.findall(text):
        v = [float(n) for n in _NUM.findall(raw)]
        matrix = _compose(matrix, _one_transform(name, v, text))
    return matrix


def _one_transform(name: str, v: list[float], text: str) -> Matrix:
    if name == "matrix" and len(v) == 6:
        return (v[0], v[1], v[2], v[3], v[4], v[5])
    if name == "translate" and v:
        return (1, 0, 0, 1, v[0], v[1] if len(v) > 1 else 0.0)
    if name == "scale" and v:
        return (v[0], 0, 0, v[1] if len(v) > 1 else v[0], 0, 0)
    if name == "rotate" and v:
        a = math.radians(v[0])
        c, s = math.cos(a), math.sin(a)
        rot: Matrix = (c, s, -s, c, 0, 0)
        if len(v) == 3:
            return _compose(_compose((1, 0, 0, 1, v[1], v[2]), rot), (1, 0, 0, 1, -v[1], -v[2]))
        return rot
    if name == "skewX" and v:
        return (1, 0, math.tan(math.radians(v[0])), 1, 0, 0)
    if name == "skewY" and v:
        return (1, math.tan(math.radians(v[0])), 0, 1, 0, 0)
    raise KbError(f"malformed SVG transform {text!r}")


def _compose(m: Matrix, n: Matrix) -> Matrix:
    a, b, c, d, e, f = m
    a2, b2, c2, d2, e2, f2 = n
    return (a * a2 + c * b2, b * a2 + d * b2, a * c2 + c * d2, b * c2 + d * d2,
            a * e2 + c * f2 + e, b * e2 + d * f2 + f)


def _apply(m: Matrix, x: float, y: float) -> Point:
    a, b, c, d, e, f = m
    return (a * x + c * y + e, b * x + d * y + f)


def _float(text: str, where: str) -> float:
    match = _NUM.match(text.strip())
    if not match:
        raise KbError(f"expected a number in {where}, got {text!r}")
    return float(match.group(0))


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]
