"""What the app runs on: settings, the KB, the event hub and the dialogues.

Built by the app's lifespan (blocking work, run off the event loop) and stopped with it.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from api.accesslog import redact_client_logs
from api.client import ServiceClient
from api.courier import DeliveryConfig
from api.relay import IntentRelay
from api.settings import Settings, SettingsError
from api.subscriptions import EventHub
from api.webhooks import Webhooks
from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.initiative import Initiative, InitiativeConfig
from dialogue.llm.base import ChatModel
from dialogue.llm.spec import SpecError, parse_spec
from dialogue.memory.learn import Memory
from dialogue.memory.people import People
from dialogue.memory.reconcile import Reconciler
from dialogue.pushed.bus import IntentBus, clock_first
from dialogue.sessions.manager import DialogueManager
from dialogue.sessions.observers import TurnObserver
from dialogue.sessions.sparql import SparqlSessions
from kb import KB, KbError
from kb.errors import StorageError
from kb.gcpause import settle
from kb.journal import Journal
from kb.protocol import KnowledgeBase
from kb.reasonbudget import ReasoningBounds
from kb.sparqlstore.endpoint import SparqlEndpoint
from kb.sparqlstore.mirror import SparqlMirror
from kb.sparqlstore.remote import RemoteKB
from kb.status import Components, ComponentStatus
from kb.tboxbudget import TBoxBounds
from kb.writer import CommitListener
from scene.textfile import load_scene
from scene.world import World

log = logging.getLogger("situated.api")


@dataclass
class Services:
    settings: Settings
    kb: KnowledgeBase
    hub: EventHub
    dialogues: DialogueManager
    world: World | None  # None on a reader: the writer keeps the scene
    journal: Journal | None
    owns_kb: bool
    store: Store | None = None
    #: The model was built from the settings (not passed in): `aclose` closes it (its HTTP client,
    #: its worker process).
    owns_model: bool = False
    # Named statuses of I/O and background work, rendered by /health (journal, compaction...).
    components: Components = field(default_factory=Components)
    #: The in-process KB of a standalone service or a writer (None on a reader): the one the
    #: journal snapshots.
    local_kb: KB | None = None
    #: Every intent emitted, numbered and buffered for the stream (GET /intents/stream); None on a
    #: reader, whose stream is the writer's.
    bus: IntentBus | None = None
    webhooks: Webhooks | None = None
    #: A reader's: the intents of its turns handed to the writer's bus.
    relay: IntentRelay | None = None
    #: Engaging and greeting people who become engaged (None on a reader: the writer does it).
    initiative: Initiative | None = None
    #: Each person's memory across dialogues (follows the KB's commits).
    people: People | None = None
    #: Retracts told values that perception later contradicts (None on a reader).
    reconciler: Reconciler | None = None

    @property
    def model(self) -> ChatModel:
        return self.dialogues.engine.model

    def clear(self, keep_defaults: bool) -> None:
        self.kb.clear(keep_defaults)  # refused whole, or done and durable
        if self.world is not None:
            try:
                self.world.sync.resync()
            except StorageError as exc:
                # The clear is acknowledged; the scene's facts come back with the next scene
                # change (the sync asserts every fact it no longer has) or at the next start.
                log.warning("the scene's facts were not asserted again after a clear: %s", exc)

    async def aclose(self) -> None:
        """Stop: the model on the event loop that used it (its HTTP client belongs to that loop),
        then the rest off the loop."""
        try:
            if self.owns_model:
                await self.model.aclose()
        finally:
            await asyncio.to_thread(self.stop)

    def stop(self) -> None:
        """Stop everything but the model (blocking), which `aclose` closes first."""
        self.dialogues.engine.close()
        if self.world is not None:
            self.world.stop()
        if self.initiative is not None:
            self.initiative.stop()
        if self.people is not None:
            self.people.close()
        if self.reconciler is not None:
            self.reconciler.stop()
        if self.webhooks is not None:
            self.webhooks.stop()
        if self.relay is not None:
            self.relay.stop()
        if self.bus is not None:
            self.bus.shutdown()
        self.hub.shutdown()
        if self.journal is not None:
            if self.local_kb is not None:
                try:
                    self.journal.snapshot(self.local_kb)  # a clean stop leaves a compact data directory
                except StorageError as exc:  # the journal alone is complete
                    log.warning("no snapshot at stop, the journal is kept as it is: %s", exc)
            self.journal.close()
        if self.owns_kb:
            self.kb.close()
        if self.store is not None:
            self.store.close()


def mirror_status(mirror: SparqlMirror) -> ComponentStatus:
    """The store mirror as a /health component: degraded while the store is unreachable or the
    mirror reconciles after a write whose outcome is unknown."""
    status = mirror.status()
    if status.in_sync:
        return ComponentStatus()
    return ComponentStatus(ok=False, code="store_out_of_sync", since=status.since,
                           reason=f"store unreachable or being reconciled: {status.refused} writes refused "
                                  f"since start; last error: {status.error}")


@dataclass
class Store:
    """The shared SPARQL store of a scaled-out service: the writer's mirror or the reader's link."""

    endpoint: SparqlEndpoint
    mirror: SparqlMirror | None = None
    writer: ServiceClient | None = None

    @property
    def role(self) -> str:
        return "writer" if self.mirror is not None else "reader"

    def close(self) -> None:
        if self.mirror is not None:
            self.mirror.detach()
        if self.writer is not None:
            self.writer.close()
        self.endpoint.close()


def event_hub(kb: KnowledgeBase, settings: Settings,
              commits: Callable[[CommitListener], Callable[[], None]] | None = None) -> EventHub:
    """Event subscribers of the service, each held to its query limits; ``commits`` follows the
    writer's commits (None on a reader, which has no commit feed)."""
    limits = settings.limits
    return EventHub(kb, limits.max_subscribers, query_timeout=limits.query_timeout, max_rows=limits.max_rows,
                    commits=commits)


def _open_journal(kb: KB, folder: Path, snapshot_records: int) -> Journal:
    journal = Journal(folder)
    found = journal.recover(kb)
    journal.compact_every(kb, snapshot_records)
    log.info("recovered the KB from %s: revision %d, %d journal records", folder, found.revision,
             found.records)
    if found.dropped_bytes:
        log.warning("dropped an incomplete last journal record (%d bytes): a write that was never "
                    "acknowledged, cut off by a crash", found.dropped_bytes)
    return journal


def backend_of(settings: Settings) -> ChatModel:
    """The model ``settings.llm`` names."""
    try:
        return parse_spec(settings.llm).model
    except SpecError as exc:
        raise SettingsError(f"llm: {exc}") from exc


def intent_bus(settings: Settings) -> IntentBus:
    """The service's intent bus, numbered from the clock: a restart is told apart from a resume."""
    return IntentBus(settings.intents.buffer, max_readers=settings.intents.max_readers, first=clock_first(),
                     buffer_bytes=settings.intents.buffer_bytes)


def build_dialogues(settings: Settings, kb: KnowledgeBase, model: ChatModel | None = None,
                    endpoint: SparqlEndpoint | None = None, intents: TurnObserver | None = None,
                    people: People | None = None) -> DialogueManager:
    """The dialogue engine on this KB, with ``model`` or the backend ``settings.llm`` names;
    with a shared store, the dialogue sessions live in it (every process sees every dialogue).
    What people say is learnt under the trust policy, each speaker's memory kept in the KB, and
    every turn's intents pushed by ``intents`` (the bus's observer, or a reader's relay)."""
    memory = Memory(kb, settings.memory.trust)
    engine = DialogueEngine(kb, model or backend_of(settings), EngineConfig(deadline=settings.deadline),
                            memory=memory)
    limits = settings.limits
    store = SparqlSessions(endpoint, max_dialogues=limits.max_dialogues) if endpoint is not None else None
    people = people if people is not None else People(kb, settings.memory.refresh)
    # The intents first: pushed at once, whatever the memory's write waits for.
    observers = [*([intents] if intents is not None else []), people.observe]
    return DialogueManager(engine, max_dialogues=limits.max_dialogues, max_turns=limits.max_history_turns,
                           store=store, observers=observers, recall=people.recall_note)


def delivery_config(settings: Settings) -> DeliveryConfig:
    """How the webhooks, and a reader's relay to the writer, deliver intents."""
    intents = settings.intents
    return DeliveryConfig(intents.webhook_retries, intents.webhook_backoff, intents.webhook_max_backoff,
                          intents.webhook_queue, intents.webhook_timeout)


def _webhooks(settings: Settings, bus: IntentBus, services: Services) -> None:
    """Start the outgoing webhooks, each a /health component."""
    intents = settings.intents
    if not intents.webhooks:
        return
    hooks = Webhooks(intents.webhooks, delivery_config(settings))
    hooks.start()
    bus.on_publish(hooks.enqueue)
    services.webhooks = hooks
    for n, hook in enumerate(hooks.hooks):
        services.components.register(f"webhook_{n}", hook.status)


def start_services(settings: Settings, kb: KB | None = None, model: ChatModel | None = None) -> Services:
    """Build the services (blocking) for the process's role (Settings.role)."""
    redact_client_logs()  # webhook and model server URLs may hold secrets; httpx logs every URL
    if settings.role == "reader":
        return _start_reader(settings, model)
    owns_kb = kb is None
    limits = settings.limits
    bounds = TBoxBounds(limits.max_tbox_triples, limits.max_tbox_links, limits.max_tbox_depth)
    the_kb = kb if kb is not None else KB(max_models_per_write=limits.max_models,
                                          max_models=limits.max_total_models,
                                          max_model_statements=limits.max_model_statements,
                                          tbox_bounds=bounds,
                                          reasoning_bounds=ReasoningBounds(
                                              limits.max_reasoning_steps,
                                              limits.max_reasoning_steps_per_statement))
    journal: Journal | None = None
    store: Store | None = None
    bus = intent_bus(settings)
    try:
        if settings.store is not None:
            store = Store(SparqlEndpoint(settings.store, settings.store_timeout), mirror=None)
        people = People(the_kb, settings.memory.refresh)
        dialogues = build_dialogues(settings, the_kb, model, store.endpoint if store else None, bus.observe,
                                    people)
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
    except (KbError, SettingsError):  # DataCorrupt included: a damaged data directory
        if journal is not None:
            journal.close()
        if store is not None:
            store.close()
        if owns_kb:
            the_kb.close()
        raise
    hub = event_hub(the_kb, settings, commits=the_kb.on_commit)
    services = Services(settings=settings, kb=the_kb, hub=hub, dialogues=dialogues, world=world,
                        journal=journal, owns_kb=owns_kb, store=store, owns_model=model is None,
                        local_kb=the_kb, bus=bus, people=people)
    people.follow()  # the KB is recovered and loaded: the index starts from it
    # The grounding follows the KB's commits on a worker thread, which makes the first snapshot
    # (the one full build) now, while the service starts; a turn that comes before it waits for it.
    # Once built, the KB and the grounding are what the service keeps: out of the collector's way.
    dialogues.engine.follow(built=settle)
    services.reconciler = Reconciler(dialogues.engine.memory)
    services.reconciler.start()
    services.initiative = Initiative(the_kb, bus, InitiativeConfig(settings.memory.greet,
                                                                   settings.memory.greet_interval),
                                     language=dialogues.engine.language)
    services.initiative.start()
    _webhooks(settings, bus, services)
    if journal is not None:
        services.components.register("storage", journal.storage_status)
        services.components.register("compaction", journal.compaction.get)
    services.components.register("expiry", the_kb.writer.expiry_status.get)
    if store is not None and store.mirror is not None:
        mirror = store.mirror
        services.components.register("store_mirror", lambda: mirror_status(mirror))
    return services


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
    if settings.intents.webhooks:
        log.info("the webhooks are the writer's (every intent of the deployment is on its stream); "
                 "this reader ignores them")
    endpoint = SparqlEndpoint(settings.store, settings.store_timeout)
    token = settings.token.get_secret_value() if settings.token else None
    writer = ServiceClient(settings.writer_url, token, name="writer")
    store = Store(endpoint, writer=writer)
    kb = RemoteKB(endpoint, writes=writer)
    config = delivery_config(settings)
    relay = IntentRelay(ServiceClient(settings.writer_url, token, config.timeout, name="writer"), config)
    people = People(kb, settings.memory.refresh)  # closed with the services: what waits is written
    try:
        dialogues = build_dialogues(settings, kb, model, endpoint, relay.observe, people)
    except SettingsError:
        relay.stop()
        kb.close()
        store.close()
        raise
    hub = event_hub(kb, settings)
    services = Services(settings=settings, kb=kb, hub=hub, dialogues=dialogues, world=None, journal=None,
                        owns_kb=True, store=store, owns_model=model is None, people=people, relay=relay)
    relay.start()
    services.components.register("intent_relay", relay.status)
    return services
