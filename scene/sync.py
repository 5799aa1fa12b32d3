"""A scene kept in sync with the KB: every change is applied as one batch of fact differences.

The scene's facts are state (S3): ``resync`` re-asserts them all after a KB clear or restart.
Entities are validated before anything changes — ids are KB names that no non-scene fact uses
yet, classes are classes the KB knows — so a bad request changes nothing.
"""

from __future__ import annotations

import json
import math
import threading
from collections.abc import Iterable, Mapping
from typing import Any

from kb.errors import KbError
from kb.kb import KB
from kb.terms import parse_name
from scene.engagement import EngagementConfig, EngagementTracker, Transition
from scene.scene import ROBOT_ID, Diff, Entity, Kind, Scene, SceneConfig

MAX_METRES = 1e6  # far beyond any room; squared distances of larger values overflow

ENGAGEMENT_PROPERTY = "engagementLevel"
_FIELDS = {"id", "kind", "class", "label", "x", "y", "heading", "width", "depth", "z"}
_OUTPUT_ONLY = {"engagement"}  # in GET /scene answers; ignored when a scene is read back


class SceneSync:
    """The scene, its facts in the KB, and the engagement of the people in it."""

    def __init__(self, kb: KB, config: SceneConfig | None = None,
                 engagement: EngagementConfig | None = None) -> None:
        self.kb = kb
        self.scene = Scene(config)
        self.tracker = EngagementTracker(engagement)
        self._lock = threading.RLock()
        self._known_classes: set[str] = set()
        self._asserted: set[str] = set()
        #: The scene has been put in the KB (loaded, adopted or changed): a clear must bring its
        #: facts back. A service started without a scene (`--scene none`) has none to bring back.
        self._in_kb = False
        self._levels_unwritten = False

    # --- whole scene -----------------------------------------------------------------------

    def replace(self, entities: Iterable[Entity], config: SceneConfig | None = None) -> Diff:
        """Replace every entity (the robot stays); one KB batch."""
        entities = list(entities)
        with self._lock:
            ids = [e.id for e in entities]
            duplicates = sorted({i for i in ids if ids.count(i) > 1})
            if duplicates:
                raise KbError(f"the scene has several entities named {', '.join(duplicates)} (S4)")
            for entity in entities:
                self._check(entity)
            scene = Scene(config or self.scene.config)
            for entity in entities:
                scene.put(entity)
            self.tracker = EngagementTracker(self.tracker.config)
            return self._commit(scene)

    def adopt(self, entities: Iterable[Entity], previous: Iterable[Entity] = ()) -> Diff:
        """Take over a scene whose facts a previous run asserted (recovered from a journal): the
        facts missing from the KB are asserted again, engagement levels start over. With
        ``previous`` (the scene before a change a crash may have cut off), the facts of that
        scene which this one does not make are retracted too, so the KB ends as this scene."""
        with self._lock:
            scene = Scene(self.scene.config)
            for entity in entities:
                scene.put(entity)
            facts = scene.facts()
            before = Scene(self.scene.config)
            for entity in previous:
                before.put(entity)
            stale = before.facts() - facts if previous else set()
            diff = Diff(added={f for f in facts if not self.kb.is_asserted(f)},
                        removed={f for f in stale if self.kb.is_asserted(f)})
            for entity in scene:
                if entity.kind is Kind.PERSON:
                    for row in self.kb.find(f"{entity.id} {ENGAGEMENT_PROPERTY} ?level"):
                        diff.removed.add(f"{entity.id} {ENGAGEMENT_PROPERTY} {row['level']}")
            if diff:
                self.kb.apply(sorted(diff.added), sorted(diff.removed))
            self.scene = scene
            self._asserted = facts
            self._in_kb = True
            self.tracker = EngagementTracker(self.tracker.config)
            return diff

    def resync(self) -> Diff:
        """Assert the scene's whole fact set again after a KB clear; nothing when the scene was never
        put in the KB."""
        with self._lock:
            if not self._in_kb:
                return Diff()
            self._asserted = set()
            return self._commit(self.scene)

    # --- one entity ------------------------------------------------------------------------

    def put(self, entity: Entity) -> Diff:
        with self._lock:
            self._check(entity)
            previous = self.scene.get(entity.id)
            change = self.scene.put(entity)
            try:
                return self._commit(self.scene, change)
            except KbError:
                self._undo(entity.id, previous)
                raise

    def remove(self, entity_id: str) -> Diff:
        with self._lock:
            previous = self.scene.get(entity_id)
            if previous is None:
                raise KbError(f"no entity {entity_id!r} in the scene")
            if entity_id == ROBOT_ID:
                raise KbError("the robot cannot be removed from the scene")
            change = self.scene.remove(entity_id)
            try:
                return self._commit(self.scene, change)
            except KbError:
                self.scene.put(previous)
                raise

    def tick(self) -> tuple[Diff, list[Transition]]:
        """One engagement sample for every person; level changes are written to the KB."""
        with self._lock:
            people = [e for e in self.scene if e.kind is Kind.PERSON]
            transitions = self.tracker.observe(people)
            for change in transitions:
                level = change.after.individual
                facts = [f"{change.person} {ENGAGEMENT_PROPERTY} {level}"] if level else []
                self.scene.set_extra(change.person, facts)
            if not transitions and not self._levels_unwritten:
                return Diff(), transitions
            self._levels_unwritten = True  # until the KB takes them (a store may refuse)
            diff = self._commit(self.scene)
            self._levels_unwritten = False
            return diff, transitions

    # --- internals -------------------------------------------------------------------------

    def _commit(self, scene: Scene, change: Diff | None = None) -> Diff:
        """Apply the difference between what the KB holds from the scene and the scene's facts
        (``change``, when the scene already computed it) as one KB batch."""
        if change is None:
            facts = scene.facts()
            diff = Diff(added=facts - self._asserted, removed=self._asserted - facts)
        else:
            diff = Diff(added=change.added - self._asserted, removed=change.removed & self._asserted)
            facts = (self._asserted - diff.removed) | diff.added
        if diff:
            self.kb.apply(sorted(diff.added), sorted(diff.removed))
        self.scene = scene
        self._asserted = facts
        self._in_kb = True
        return diff

    def _undo(self, entity_id: str, previous: Entity | None) -> None:
        if previous is None:
            self.scene.remove(entity_id)
        else:
            self.scene.put(previous)

    def _check(self, entity: Entity) -> None:
        where = f"scene entity {entity.id!r}"
        if entity.kind is Kind.ROBOT or entity.id == ROBOT_ID:
            raise KbError(f"{where}: the robot ({ROBOT_ID}) is always in the scene and is not placed")
        parse_name(entity.id, where)
        if ":" in entity.id:
            raise KbError(f"{where}: scene ids are plain names (no prefix)")
        for value in (entity.x, entity.y, entity.heading):
            if not math.isfinite(value):
                raise KbError(f"{where}: position and heading must be finite numbers")
        for size in (entity.width, entity.depth):
            if size is not None and not (math.isfinite(size) and size > 0):
                raise KbError(f"{where}: width and depth must be positive")
        if any(abs(v) > MAX_METRES for v in (entity.x, entity.y, entity.width or 0, entity.depth or 0)):
            raise KbError(f"{where}: positions and sizes are at most {MAX_METRES:g} m (the geometry "
                          "overflows beyond)")
        self._check_class(entity.cls, where)
        if entity.id not in self.scene and self._mentioned(entity.id):
            raise KbError(f"{where}: the KB already has facts about {entity.id!r} that the scene did not "
                          "make; pick another id")

    def _check_class(self, cls: str, where: str) -> None:
        if cls in self._known_classes:
            return
        parse_name(cls, f"the class of {where}")
        if self.kb.details(cls)["type"] != "class":
            raise KbError(f"{where}: unknown class {cls!r} (not a class of the KB's ontology)")
        self._known_classes.add(cls)

    def _mentioned(self, entity_id: str) -> bool:
        return self.kb.exist(f"{entity_id} ?p ?o") or self.kb.exist(f"?s ?p {entity_id}")


# --- the JSON scene format -------------------------------------------------------------------


def entity_from_json(data: Mapping[str, Any]) -> Entity:
    """``{"id", "kind", "class"?, "label"?, "x", "y", "heading"? (radians), "width"?, "depth"?,
    "z"?}``; positions in metres in the robot's frame."""
    if not isinstance(data, Mapping):
        raise KbError(f"a scene entity must be an object, got {data!r}")
    unknown = set(data) - _FIELDS - _OUTPUT_ONLY
    if unknown:
        raise KbError(f"scene entity {data.get('id')!r}: unknown fields {sorted(unknown)}")
    try:
        kind = Kind(data.get("kind", "object"))
        return Entity(
            id=str(data["id"]), kind=kind, cls=str(data.get("class") or ""), label=data.get("label"),
            x=float(data.get("x", 0.0)), y=float(data.get("y", 0.0)),
            heading=float(data.get("heading", 0.0)),
            width=None if data.get("width") is None else float(data["width"]),
            depth=None if data.get("depth") is None else float(data["depth"]),
            z=None if data.get("z") is None else int(data["z"]),
        )
    except KeyError as exc:
        raise KbError(f"scene entity {data!r}: missing field {exc}") from None
    except (TypeError, ValueError, OverflowError) as exc:
        raise KbError(f"scene entity {data.get('id')!r}: {exc}") from None


def entity_to_json(entity: Entity) -> dict[str, Any]:
    box = entity.box
    return {
        "id": entity.id, "kind": entity.kind.value, "class": entity.cls, "label": entity.label,
        "x": entity.x, "y": entity.y, "heading": entity.heading,
        "width": round(box.xmax - box.xmin, 6), "depth": round(box.ymax - box.ymin, 6), "z": entity.level,
    }


def scene_from_json(data: str | bytes | Mapping[str, Any]) -> list[Entity]:
    """``{"entities": [...]}`` (the format of ``GET /scene``)."""
    if isinstance(data, str | bytes):
        try:
            data = json.loads(data)
        except (ValueError, RecursionError) as exc:  # also bytes that are not UTF-8, deep nesting
            raise KbError(f"malformed JSON scene: {exc}") from None
    if not isinstance(data, Mapping) or not isinstance(data.get("entities"), list):
        raise KbError('a JSON scene is an object {"entities": [...]}')
    return [entity_from_json(e) for e in data["entities"]
            if not (isinstance(e, Mapping) and e.get("id") == ROBOT_ID)]


def scene_to_json(sync: SceneSync) -> dict[str, Any]:
    levels = {person: level.name.lower() for person, level in sync.tracker.levels().items()}
    entities = []
    for entity in sync.scene:
        item = entity_to_json(entity)
        if entity.kind is Kind.PERSON:
            item["engagement"] = levels.get(entity.id, "unknown")
        entities.append(item)
    config = sync.scene.config
    return {"entities": entities, "config": {
        "fov_degrees": config.fov_degrees, "range_m": config.range_m,
        "agents_in_zones": config.agents_in_zones, "zones": config.zones, "supports": config.supports,
    }}
