"""What the app runs on: settings, the KB, the event hub and the dialogues.

Built by the app's lifespan (blocking work, run off the event loop) and stopped with it.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass
from pathlib import Path

from api.forward import WriterClient
from api.kbtypes import AnyKB
from api.scenefile import load_scene
from api.settings import Settings, SettingsError
from api.subscriptions import EventHub
from api.world import World
from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.llm.base import ChatModel
from dialogue.llm.spec import SpecError, parse_spec
from dialogue.sessions import DialogueManager
from dialogue.sparqlsessions import SparqlSessions
from kb import KB, KbError
from kb.endpoint import SparqlEndpoint
from kb.journal import Journal
from kb.mirror import MirrorStatus, SparqlMirror
from kb.remote import RemoteKB

log = logging.getLogger("situated.api")


@dataclass
class Services:
    settings: Settings
    kb: AnyKB
    hub: EventHub
    dialogues: DialogueManager
    world: World | None  # None on a reader: the writer keeps the scene
    journal: Journal | None
    owns_kb: bool
    store: Store | None = None

    @property
    def model(self) -> ChatModel:
        return self.dialogues.engine.model

    def components(self) -> dict[str, ComponentStatus]:
        """The parts of the service that can be degraded while it runs, by name (for /health)."""
        found: dict[str, ComponentStatus] = {}
        if self.store is not None and self.store.mirror is not None:
            found["store_mirror"] = _mirror_status(self.store.mirror.status())
        return found

    def clear(self, keep_defaults: bool) -> None:
        self.kb.clear(keep_defaults)
        if self.world is not None:
            self.world.sync.resync()

    def stop(self) -> None:
        if self.world is not None:
            self.world.stop()
        self.hub.shutdown()
        if self.journal is not None:
            if isinstance(self.kb, KB):  # only a writer keeps a journal
                self.journal.snapshot(self.kb)  # a clean stop leaves a compact data directory
            self.journal.close()
        if self.owns_kb:
            self.kb.close()
        if self.store is not None:
            self.store.close()


@dataclass(frozen=True)
class ComponentStatus:
    """How one part of the service is doing: ``ok``, else a message saying what is wrong."""

    ok: bool
    message: str = ""


def _mirror_status(status: MirrorStatus) -> ComponentStatus:
    if status.in_sync:
        return ComponentStatus(True, f"{status.refused} writes refused since start")
    since = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime(status.since)) if status.since else "start"
    return ComponentStatus(False, f"store unreachable or being reconciled since {since}: {status.refused} "
                                  f"writes refused since start; last error: {status.error}")


@dataclass
class Store:
    """The shared SPARQL store of a scaled-out service: the writer's mirror or the reader's link."""

    endpoint: SparqlEndpoint
    mirror: SparqlMirror | None = None
    writer: WriterClient | None = None

    @property
    def role(self) -> str:
        return "writer" if self.mirror is not None else "reader"

    def close(self) -> None:
        if self.mirror is not None:
            self.mirror.detach()
        if self.writer is not None:
            self.writer.close()
        self.endpoint.close()


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


def build_dialogues(settings: Settings, kb: AnyKB, model: ChatModel | None = None,
                    endpoint: SparqlEndpoint | None = None) -> DialogueManager:
    """The dialogue engine on this KB, with ``model`` or the backend ``settings.llm`` names;
    with a shared store, the dialogue sessions live in it (every process sees every dialogue)."""
    hybrid = False
    if model is None:
        model, hybrid = backend_of(settings)
    engine = DialogueEngine(kb, model, EngineConfig(deadline=settings.deadline, hybrid=hybrid))
    limits = settings.limits
    store = SparqlSessions(endpoint, max_dialogues=limits.max_dialogues) if endpoint is not None else None
    return DialogueManager(engine, max_dialogues=limits.max_dialogues, max_turns=limits.max_history_turns,
                           store=store)


def start_services(settings: Settings, kb: KB | None = None, model: ChatModel | None = None) -> Services:
    """Build the services (blocking) for the process's role (Settings.role)."""
    if settings.role == "reader":
        return _start_reader(settings, model)
    owns_kb = kb is None
    the_kb = kb if kb is not None else KB()
    journal: Journal | None = None
    store: Store | None = None
    try:
        if settings.store is not None:
            store = Store(SparqlEndpoint(settings.store, settings.store_timeout), mirror=None)
        dialogues = build_dialogues(settings, the_kb, model, store.endpoint if store else None)
        if settings.data_dir is not None:
            journal = _open_journal(the_kb, settings.data_dir, settings.snapshot_records)
        if store is not None:
            store.mirror = _mirror(the_kb, store.endpoint, recover=owns_kb and journal is None)
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
        if store is not None:
            store.close()
        if owns_kb:
            the_kb.close()
        raise
    hub = EventHub(the_kb, settings.limits.max_subscribers)
    return Services(settings=settings, kb=the_kb, hub=hub, dialogues=dialogues, world=world,
                    journal=journal, owns_kb=owns_kb, store=store)


def _mirror(kb: KB, endpoint: SparqlEndpoint, recover: bool) -> SparqlMirror:
    """The writer's mirror. Without a journal, the store is the durable copy: what it holds is
    loaded first. Then the store is rewritten from the KB and follows every commit."""
    mirror = SparqlMirror(endpoint)
    if recover:
        revision = mirror.recover(kb)
        if revision is not None:
            log.info("recovered the KB from the store %s: revision %d", endpoint.spec.query_url, revision)
    mirror.attach(kb)
    return mirror


def _start_reader(settings: Settings, model: ChatModel | None) -> Services:
    """A reader: queries answered from the store, writes and the scene handed to the writer."""
    assert settings.store is not None and settings.writer_url is not None  # Settings.role says so
    if settings.ontology_files or settings.scene not in (None, "", "none", "demo"):
        log.info("ontology files and the scene are the writer's; this reader ignores them")
    endpoint = SparqlEndpoint(settings.store, settings.store_timeout)
    token = settings.token.get_secret_value() if settings.token else None
    writer = WriterClient(settings.writer_url, token)
    store = Store(endpoint, writer=writer)
    kb = RemoteKB(endpoint, writes=writer)
    try:
        dialogues = build_dialogues(settings, kb, model, endpoint)
    except SettingsError:
        kb.close()
        store.close()
        raise
    hub = EventHub(kb, settings.limits.max_subscribers)
    return Services(settings=settings, kb=kb, hub=hub, dialogues=dialogues, world=None, journal=None,
                    owns_kb=True, store=store)
