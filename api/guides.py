"""Which guide of ``docs/`` explains an error of the ``situated`` command: one table, so the CLI's
messages and its ``--help`` never name a guide on their own.

An error's kind is its type (or the type of the error that caused it: a bad ``--llm`` is a
``SettingsError`` caused by a ``SpecError``), unless the command said what it was reading when the
error came (``about``: a ``KbError`` while loading a scene is a scene error, not a query's).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from enum import StrEnum

from api.client import ClientError
from api.ros.cli import RosError
from api.settings import SettingsError
from dialogue.ask.form import AskError
from dialogue.errors import DialogueError
from dialogue.llm.spec import SpecError
from kb.errors import DataCorrupt, KbError, StorageError, StoreUnavailable

DOCS = "docs"


class Kind(StrEnum):
    """What an error is about, each explained by one guide."""

    SETUP = "getting-started.md"
    KB = "knowledge-base.md"
    DIALOGUE = "dialogue.md"
    CHATBOT = "chatbot.md"
    MEMORY = "memory.md"
    MODELS = "models.md"
    SCENES = "scenes.md"
    ROS = "ros.md"
    SCALE_OUT = "scale-out.md"
    SECURITY = "security.md"
    BENCHMARKS = "benchmarks.md"
    EVALUATION = "evaluation.md"


#: What each guide explains (the ``--help`` epilog lists them in this order).
GUIDES: dict[Kind, str] = {
    Kind.SETUP: "install, settings, a first service and conversation",
    Kind.KB: "the knowledge base: statements, reasoning, queries, SPARQL, the data folder",
    Kind.DIALOGUE: "what the offline rules understand",
    Kind.CHATBOT: "the chatbot contract: roles, ask, stateless turns, locales, traces",
    Kind.MEMORY: "memory and initiative",
    Kind.MODELS: "using a real model (ollama, hybrid mode, each backend's needs), situated doctor",
    Kind.SCENES: "your own scene and ontology: SVG, JSON and statement files, --ontology",
    Kind.ROS: "ROS 2: situated ros install, env, run",
    Kind.SCALE_OUT: "a SPARQL store, a writer and read replicas",
    Kind.SECURITY: "tokens, limits, what is refused",
    Kind.BENCHMARKS: "situated bench",
    Kind.EVALUATION: "situated eval and the case format",
}

#: Error types and their kinds, most specific first: the first the error (or its cause) is wins.
ERROR_KINDS: tuple[tuple[type[BaseException], Kind], ...] = (
    (SpecError, Kind.MODELS),
    (RosError, Kind.ROS),
    (AskError, Kind.CHATBOT),
    (StoreUnavailable, Kind.SCALE_OUT),
    (DataCorrupt, Kind.KB),
    (StorageError, Kind.KB),
    (SettingsError, Kind.SETUP),
    (DialogueError, Kind.DIALOGUE),
    (KbError, Kind.KB),
    (ClientError, Kind.SETUP),  # a service that cannot be reached, or refuses the request
)

#: A service's refusals by HTTP status (other statuses: the request's own kind, or setting up).
CLIENT_STATUS_KINDS: dict[int, Kind] = {401: Kind.SECURITY, 403: Kind.SECURITY, 413: Kind.SECURITY,
                                        429: Kind.SECURITY}


#: `situated doctor`'s checks and the guide of each (what a failed or warned one points to).
CHECK_KINDS: dict[str, Kind] = {"kb": Kind.SCENES, "data": Kind.KB, "model": Kind.MODELS,
                                "chromium": Kind.SETUP, "port": Kind.SETUP}


class Guided(Exception):
    """An error raised while the command read something of a known kind (``about``)."""

    def __init__(self, kind: Kind, error: Exception) -> None:
        super().__init__(str(error))
        self.kind = kind
        self.error = error


@contextmanager
def about(kind: Kind, *errors: type[Exception]) -> Iterator[None]:
    """Errors of ``errors`` (default: ``KbError``) raised inside are of ``kind``."""
    caught = errors or (KbError,)
    try:
        yield
    except caught as exc:
        raise Guided(kind, exc) from exc


def _chain(error: BaseException) -> Iterator[BaseException]:
    seen: BaseException | None = error
    while seen is not None:
        yield seen
        seen = seen.__cause__


def kind_of(error: BaseException) -> Kind | None:
    """The kind of ``error``: said by ``about``, else the first of ``ERROR_KINDS`` that it or one
    of its causes is (a ``SpecError`` under a ``SettingsError`` is a model's)."""
    chain = list(_chain(error))
    for link in chain:
        if isinstance(link, Guided):
            return link.kind
        if isinstance(link, ClientError) and link.status in CLIENT_STATUS_KINDS:
            return CLIENT_STATUS_KINDS[link.status]
    return next((kind for error_type, kind in ERROR_KINDS if any(isinstance(e, error_type) for e in chain)),
                None)


def guide(kind: Kind) -> str:
    """The guide's path in a clone."""
    return f"{DOCS}/{kind.value}"


def see(error: BaseException) -> str:
    """What to append to the message of ``error``: where it is explained, or nothing."""
    kind = kind_of(error)
    return "" if kind is None else f" (see {guide(kind)})"


def listing() -> str:
    """The guides, one a line, for ``--help``."""
    width = max(len(guide(kind)) for kind in GUIDES)
    return "\n".join(f"  {guide(kind):<{width}}  {what}" for kind, what in GUIDES.items())
