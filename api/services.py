"""What the app runs on: settings, the KB, the event hub and the dialogues.

Built by the app's lifespan (blocking work, run off the event loop) and stopped with it.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from pathlib import Path

from api.scenefile import load_scene
from api.settings import Settings, SettingsError
from api.subscriptions import EventHub
from api.world import World
from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.llm.base import ChatModel
from dialogue.llm.spec import SpecError, parse_spec
from dialogue.sessions import DialogueManager
from kb import KB, KbError
from kb.journal import Journal

log = logging.getLogger("situated.api")


@dataclass
class Services:
    settings: Settings
    kb: KB
    hub: EventHub
    dialogues: DialogueManager
    world: World
    journal: Journal | None
    owns_kb: bool

    @property
    def model(self) -> ChatModel:
        return self.dialogues.engine.model

    def clear(self, keep_defaults: bool) -> None:
        self.kb.clear(keep_defaults)
        self.world.sync.resync()

    def stop(self) -> None:
        self.world.stop()
        self.hub.shutdown()
        if self.journal is not None:
            self.journal.snapshot(self.kb)  # a clean stop leaves a compact data directory
            self.journal.close()
        if self.owns_kb:
            self.kb.close()


def _open_journal(kb: KB, folder: Path, snapshot_records: int) -> Journal:
    journal = Journal(folder)
    found = journal.recover(kb)
    journal.compact_every(kb, snapshot_records)
    torn = f", dropped a torn tail of {found.dropped_bytes} bytes" if found.dropped_bytes else ""
    log.info("recovered the KB from %s: revision %d, %d journal records%s", folder, found.revision,
             found.records, torn)
    return journal


def backend_of(settings: Settings) -> tuple[ChatModel, bool]:
    """The model ``settings.llm`` names and whether it runs behind the rules (hybrid)."""
    try:
        backend = parse_spec(settings.llm)
    except SpecError as exc:
        raise SettingsError(f"llm: {exc}") from exc
    return backend.model, backend.hybrid


def build_dialogues(settings: Settings, kb: KB, model: ChatModel | None = None) -> DialogueManager:
    """The dialogue engine on this KB, with ``model`` or the backend ``settings.llm`` names."""
    hybrid = False
    if model is None:
        model, hybrid = backend_of(settings)
    engine = DialogueEngine(kb, model, EngineConfig(deadline=settings.deadline, hybrid=hybrid))
    return DialogueManager(engine, max_dialogues=settings.limits.max_dialogues,
                           max_turns=settings.limits.max_history_turns)


def start_services(settings: Settings, kb: KB | None = None, model: ChatModel | None = None) -> Services:
    """Build the services (blocking): the KB (recovered from the data directory), extra
    ontologies, the scene and its engagement ticker, the event hub and the dialogues."""
    owns_kb = kb is None
    the_kb = kb if kb is not None else KB()
    journal: Journal | None = None
    try:
        dialogues = build_dialogues(settings, the_kb, model)
        if settings.data_dir is not None:
            journal = _open_journal(the_kb, settings.data_dir, settings.snapshot_records)
        for path in settings.ontology_files:
            the_kb.load(str(path))
        world = World(the_kb, settings.scene_settings, settings.data_dir)
        source = settings.scene if settings.scene not in (None, "", "none") else None
        if source is not None and source.endswith(".txt"):
            count = load_scene(the_kb, Path(source))
            log.info("loaded %d scene statements from %s", count, source)
            source = None
        world.start(source)
    except (KbError, SettingsError):
        if journal is not None:
            journal.close()
        if owns_kb:
            the_kb.close()
        raise
    hub = EventHub(the_kb, settings.limits.max_subscribers)
    return Services(settings=settings, kb=the_kb, hub=hub, dialogues=dialogues, world=world,
                    journal=journal, owns_kb=owns_kb)
