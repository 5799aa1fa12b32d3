"""The service's scene: loading it, keeping it across restarts, and the engagement ticker.

The scene comes from settings (``demo``: the packaged demo environment; an ``.svg`` in the
simulator's format; a ``.json`` scene; ``none``). With a data directory, the current scene is
kept in ``scene.json`` after every change, and at start it takes over the facts the previous
run's scene left in the (recovered) KB, so a restart leaves nothing stale behind.
"""

from __future__ import annotations

import json
import logging
import os
import threading
from collections.abc import Callable
from importlib.resources import files
from pathlib import Path
from typing import Any

from kb import KB, KbError
from kb.errors import StorageError, storage_error
from kb.terms import parse_ground
from scene.engagement import Transition
from scene.scene import ROBOT_ID, Diff, Entity, Kind, SceneConfig
from scene.settings import SceneSettings
from scene.svg import load_svg
from scene.sync import SceneSync, entity_from_json, entity_to_json, scene_from_json, scene_to_json
from scene.textfile import load_scene, read_statements

log = logging.getLogger("situated.scene")
SCENE_FILE = "scene.json"
PENDING_FILE = "scene.pending.json"  # a scene change written ahead of its KB commit
DEMO = "demo"


#: What a scene source may be, as every message says it.
SCENE_KINDS = "'demo', an .svg environment, a .json scene, a .txt file of statements, or 'none'"


def read_scene(source: str) -> list[Entity]:
    """Entities from ``demo``, an ``.svg`` file or a ``.json`` file."""
    if source == DEMO:
        return load_svg((files("ontologies") / "demo.svg").read_bytes())
    path = Path(source)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise KbError(f"cannot read scene {source!r}: {exc.strerror}") from exc
    if path.suffix.lower() == ".svg":
        return load_svg(data)
    if path.suffix.lower() == ".json":
        return scene_from_json(data)
    raise KbError(f"scene {source!r}: use {SCENE_KINDS}")


def check_scene(source: str | None) -> None:
    """Read and parse a scene source as a start would load it, without a KB, so that a bad one is
    said in one line before anything starts (KbError saying what is wrong)."""
    if source in (None, "", "none", DEMO):
        return
    assert source is not None
    if not source.endswith(".txt"):
        read_scene(source)
        return
    for statement in read_statements(Path(source)):
        try:
            parse_ground(statement)
        except KbError as exc:
            raise KbError(f"scene {source!r}: {exc}") from None


def load_any_scene(kb: KB, source: str) -> str:
    """Load a scene of any kind into a KB (the CLI's in-process mode); says what was loaded."""
    if source.endswith(".txt"):
        return f"loaded {load_scene(kb, Path(source))} statements from {source}"
    entities = read_scene(source)
    SceneSync(kb).replace(entities)
    return f"loaded {len(entities)} scene entities from {source}"


def scene_config(settings: SceneSettings) -> SceneConfig:
    return SceneConfig(fov_degrees=settings.fov_degrees, range_m=settings.range_m,
                       agents_in_zones=settings.agents_in_zones, zones=settings.zones,
                       supports=settings.supports)


class World:
    """A ``SceneSync`` plus persistence and a background engagement ticker."""

    def __init__(self, kb: KB, settings: SceneSettings, data_dir: Path | None) -> None:
        self.sync = SceneSync(kb, scene_config(settings))
        self._lock = threading.Lock()
        self._file = data_dir / SCENE_FILE if data_dir is not None else None
        self._pending = data_dir / PENDING_FILE if data_dir is not None else None
        self._hz = settings.engagement_hz
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self.transitions: list[Transition] = []
        self._unsaved = False  # a change is in the pending file only (its save failed)

    def start(self, source: str | None) -> None:
        """Load the persisted scene if there is one, else ``source``; finish a change a crash
        interrupted; start ticking."""
        if self._file is not None and self._file.exists():
            previous = scene_from_json(self._file.read_bytes())
            self.sync.adopt(previous)
            log.info("restored the scene from %s (%d entities)", self._file, len(previous))
        elif source is not None:
            entities = read_scene(source)
            diff = self.replace(entities)
            log.info("loaded the scene %s: %d entities, %d facts", source, len(entities), len(diff.added))
        self._finish_pending()
        if self._hz > 0:
            self._thread = threading.Thread(target=self._tick_loop, name="scene-engagement", daemon=True)
            self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)

    def replace(self, entities: list[Entity]) -> Diff:
        op = {"op": "replace", "entities": [entity_to_json(e) for e in entities]}
        return self._change(op, lambda: self.sync.replace(entities))

    def put(self, entity: Entity) -> Diff:
        return self._change({"op": "put", "entity": entity_to_json(entity)}, lambda: self.sync.put(entity))

    def remove(self, entity_id: str) -> Diff:
        return self._change({"op": "remove", "id": entity_id}, lambda: self.sync.remove(entity_id))

    def _change(self, op: dict[str, Any], apply: Callable[[], Diff]) -> Diff:
        """Apply a change to the KB and save the scene. The change is written ahead: a crash
        between the KB commit and the save is finished at the next start, instead of leaving KB
        facts about an entity the saved scene does not know (which nothing would retract)."""
        with self._lock:
            if self._unsaved:  # the last change is only in the pending file: save it before
                self._save()   # writing ahead another, or refuse this one (nothing changed)
            self._write(self._pending, op)
            try:
                diff = apply()
            except KbError:  # StorageError included: the KB refused it whole
                self._drop_pending()
                raise
            try:
                self._save()
            except StorageError as exc:
                # The change is durable (journal + pending file, which a start finishes), so
                # it is acknowledged; the save is retried before the next change.
                self._unsaved = True
                log.warning("scene saved only as a pending change: %s", exc)
            return diff

    def _finish_pending(self) -> None:
        """Bring the KB and the scene to the state after the change written ahead, whether or
        not its KB commit happened before the crash."""
        if self._pending is None or not self._pending.exists():
            return
        current = [e for e in self.sync.scene if e.id != ROBOT_ID]
        try:
            op = json.loads(self._pending.read_bytes())
            if op["op"] == "put":
                entity = entity_from_json(op["entity"])
                target = [e for e in current if e.id != entity.id] + [entity]
            elif op["op"] == "remove":
                target = [e for e in current if e.id != op["id"]]
            else:
                target = scene_from_json({"entities": op["entities"]})
            with self._lock:
                self.sync.adopt(target, previous=current)
                self._save()
            log.info("finished the scene change a stop interrupted (%s)", op["op"])
        except (ValueError, KeyError, TypeError, KbError) as exc:
            log.warning("dropped an unreadable interrupted scene change: %s", exc)
            self._drop_pending()

    def tick(self) -> Diff:
        with self._lock:
            diff, transitions = self.sync.tick()
            self.transitions.extend(transitions)
            del self.transitions[:-100]  # only the latest are of interest
            return diff

    def _tick_loop(self) -> None:
        period = 1.0 / self._hz
        while not self._stop.wait(period):
            if any(e.kind is Kind.PERSON for e in self.sync.scene):
                try:
                    self.tick()
                except KbError as exc:  # the store refused: the next tick writes the levels again
                    log.warning("engagement levels not written: %s", exc)

    def _save(self) -> None:
        self._write(self._file, scene_to_json(self.sync))
        self._drop_pending()
        self._unsaved = False

    def _drop_pending(self) -> None:
        if self._pending is not None:
            self._pending.unlink(missing_ok=True)

    @staticmethod
    def _write(path: Path | None, data: dict[str, Any]) -> None:
        """Replace ``path`` with ``data`` whole (a new file renamed over it), durably."""
        if path is None:
            return
        tmp = path.with_suffix(".tmp")
        try:
            with tmp.open("wb") as handle:
                handle.write(json.dumps(data).encode())
                handle.flush()
                os.fsync(handle.fileno())
            os.replace(tmp, path)
        except OSError as exc:
            tmp.unlink(missing_ok=True)
            raise storage_error(exc, path.parent, "the scene change") from exc
