"""Service settings: defaults < config file (TOML or JSON) < ``SITUATED_*`` env vars < explicit values.

Nested limits are set from the environment with a double underscore, e.g.
``SITUATED_LIMITS__MAX_BODY_BYTES=2000000``; lists as JSON, e.g. ``SITUATED_CORS_ORIGINS='["http://a"]'``.
"""

from __future__ import annotations

import json
import os
import tomllib
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, Field, SecretStr, ValidationError, field_validator, model_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

from kb.errors import KbError
from kb.sparqlstore.endpoint import StoreSpec
from scene.settings import SceneSettings

CONFIG_ENV = "SITUATED_CONFIG"


class Limits(BaseModel):
    """Bounds on what one request or client may ask for (exceeding one is a clear 413/429)."""

    max_body_bytes: int = Field(default=1_048_576, ge=1024, description="largest request body accepted")
    max_statements: int = Field(default=1000, ge=1, description="statements per revise request")
    max_patterns: int = Field(default=32, ge=1, description="patterns per query or subscription")
    max_subscribers: int = Field(default=64, ge=1, description="concurrent SSE + WebSocket event subscribers")
    max_history_turns: int = Field(default=50, ge=1, description="turns of history kept per dialogue")
    max_dialogues: int = Field(default=1000, ge=1, description="dialogues open at once")
    max_rows: int = Field(default=10_000, ge=1, description="rows a /kb/query or /sparql answer or an event "
                          "subscription may have (triples, for a CONSTRUCT or DESCRIBE)")
    query_timeout: float = Field(default=5.0, gt=0, le=600, description="seconds a /kb/query or /sparql "
                                 "query or an event subscription's evaluation may take, waiting for the KB "
                                 "included; a write waits about this long behind queries, a commit about "
                                 "this long for subscriptions")
    max_input_chars: int = Field(default=4000, ge=1, description="characters in one utterance")
    max_models: int = Field(default=16, ge=1, description="models named in one write or query (each new "
                            "model is a copy of the ontology's closure)")
    max_total_models: int = Field(default=256, ge=2, description="models the KB holds, the robot's own "
                                  "included (one per person who told the robot something, each about 1 MB "
                                  "with the default ontology); a write making more is refused "
                                  "(413 model_limit)")
    max_model_statements: int = Field(default=1000, ge=1, description="statements of its own a model "
                                      "other than the robot's holds (a person's beliefs); a write past it "
                                      "is refused (413 model_limit)")
    max_tbox_triples: int = Field(default=20_000, ge=1, description="schema triples (subclasses, domains, "
                                  "RDF list items...) one write may change in a model: each write that "
                                  "changes the TBox recompiles it and re-reasons the model under the KB lock")
    max_tbox_links: int = Field(default=50_000, ge=1, description="superclass and superproperty links the "
                                "TBox a write makes may hold in all (they grow with the square of a "
                                "hierarchy's depth)")
    max_tbox_depth: int = Field(default=256, ge=1, description="superclasses of one class (superproperties "
                                "of one property) the TBox a write makes may give")
    max_reasoning_steps: int = Field(default=200_000, ge=1, description="derivation steps the reasoner "
                                     "may take for one write's facts, plus max_reasoning_steps_per_statement "
                                     "for each statement it writes (facts along a transitive property "
                                     "close into the square of their chain's length); a write past it is "
                                     "refused (413 reasoning_too_large)")
    max_reasoning_steps_per_statement: int = Field(default=16, ge=1, description="derivation steps each "
                                                   "statement of a write adds to its allowance (a bulk "
                                                   "load takes 5 to 9)")


class IntentSettings(BaseModel):
    """Intents pushed to the middleware: the stream's replay buffer and the outgoing webhooks."""

    buffer: int = Field(default=1000, ge=1, description="pushed intents kept for a client that "
                        "reconnects to replay (GET /intents/stream?after=N, Last-Event-ID)")
    buffer_bytes: int = Field(default=8 * 1024 * 1024, ge=4096, description="bytes (of JSON) of pushed "
                              "intents kept in that buffer, and queued for one stream client; past it the "
                              "oldest go (GET /intents answers at most about this much)")
    max_intent_bytes: int = Field(default=65_536, ge=1024, description="bytes (of JSON) of one intent, "
                                  "with its response, that POST /intents takes (413 past it)")
    max_readers: int = Field(default=64, ge=1, description="intent stream clients (SSE + WebSocket) at once")
    webhooks: list[str] = Field(default_factory=list, description="URLs each pushed intent is POSTed to")
    webhook_retries: int = Field(default=5, ge=0, le=100, description="retries of a failed delivery")
    webhook_backoff: float = Field(default=0.5, gt=0, le=60, description="seconds before the first retry; "
                                   "doubled for each next one")
    webhook_max_backoff: float = Field(default=30.0, gt=0, le=3600,
                                       description="longest wait between retries")
    webhook_queue: int = Field(default=1000, ge=1, description="intents waiting per webhook URL; past it "
                               "the oldest is dropped")
    webhook_timeout: float = Field(default=5.0, gt=0, le=60, description="seconds one delivery may take")

    @model_validator(mode="after")
    def _one_fits(self) -> IntentSettings:
        if self.max_intent_bytes > self.buffer_bytes:
            raise ValueError(f"max_intent_bytes ({self.max_intent_bytes}) must not exceed buffer_bytes "
                             f"({self.buffer_bytes}): the buffer holds at least one intent")
        return self

    @field_validator("webhooks")
    @classmethod
    def _http_urls(cls, urls: list[str]) -> list[str]:
        for url in urls:
            if not url.startswith(("http://", "https://")):
                raise ValueError(f"webhook {url!r} must be an http:// or https:// URL")
        return urls


class MemorySettings(BaseModel):
    """What the robot learns from dialogue and remembers of people, and its initiative."""

    trust: Literal["all", "people", "none"] = Field(default="people", description="whose statements the "
                                                    "robot adopts as its own knowledge: all, people (what a "
                                                    "person says of themself and their own things) or none")
    refresh: float = Field(default=60.0, ge=0, description="seconds between two writes of a person's "
                           "lastSpokeAt when their turns have nothing to note")
    greet: bool = Field(default=True, description="greet a person who becomes engaged (by name if known)")
    greet_interval: float = Field(default=300.0, ge=0, description="seconds before the same person is "
                                  "greeted again")


class Settings(BaseSettings):
    """Everything the service reads at start; see the module docstring for precedence."""

    model_config = SettingsConfigDict(env_prefix="SITUATED_", env_nested_delimiter="__", extra="forbid")

    host: str = "127.0.0.1"
    port: int = Field(default=8000, ge=0, le=65535)
    data_dir: Path | None = Field(default=None, description="durable KB: journal and snapshots")
    snapshot_records: int = Field(default=50_000, ge=0, description="with a data directory: snapshot "
                                  "(compact the journal) every this many writes; 0: only at stop")
    ontology_files: list[Path] = Field(default_factory=list, description="extra RDF files loaded at start")
    scene: str | None = Field(default="demo", description="the scene at start: demo (the packaged demo "
                              "environment), an .svg environment, a .json scene, a .txt file of statements, "
                              "or none")
    scene_settings: SceneSettings = Field(default_factory=SceneSettings)
    llm: str = Field(default="rules", description="dialogue model backend spec, e.g. rules, ollama:MODEL@URL")
    deadline: float = Field(default=5.0, gt=0, le=600, description="seconds per dialogue turn")
    token: SecretStr | None = Field(default=None, description="Bearer token required for writes when set")
    allow_anonymous_reads: bool = True
    limits: Limits = Field(default_factory=Limits)
    intents: IntentSettings = Field(default_factory=IntentSettings)
    memory: MemorySettings = Field(default_factory=MemorySettings)
    cors_origins: list[str] = Field(default_factory=list)
    sparql_update: bool = False
    store: str | None = Field(default=None, description="keep the KB in a SPARQL 1.1 store, e.g. "
                              "sparql+http://127.0.0.1:7878 (see the README's scale-out section); without "
                              "writer_url this process is the one writer")
    writer_url: str | None = Field(default=None, description="with store: this process is a reader that "
                                   "answers from the store and forwards writes to the writer service here")
    store_timeout: float = Field(default=2.0, gt=0, le=60, description="with store: seconds one request "
                                 "to the store may take; shorter than deadline, so a stalled store cannot "
                                 "hold a dialogue turn past it")

    @field_validator("store")
    @classmethod
    def _store_spec(cls, store: str | None) -> str | None:
        if store is not None:
            try:
                StoreSpec.parse(store)
            except KbError as exc:
                raise ValueError(str(exc)) from None
        return store

    @field_validator("writer_url")
    @classmethod
    def _http_url(cls, url: str | None) -> str | None:
        if url is not None and not url.startswith(("http://", "https://")):
            raise ValueError("writer_url must be the writer service's http:// or https:// URL")
        return url.rstrip("/") if url else None

    @model_validator(mode="after")
    def _roles(self) -> Settings:
        if self.writer_url is not None and self.store is None:
            raise ValueError("writer_url needs store: a reader answers from the shared SPARQL store")
        if self.writer_url is not None and self.data_dir is not None:
            raise ValueError("data_dir is the writer's journal; a reader (writer_url set) keeps none")
        if self.store is not None and self.store_timeout >= self.deadline:
            raise ValueError(f"store_timeout ({self.store_timeout:g} s) must be shorter than deadline "
                             f"({self.deadline:g} s): a dialogue turn waits on the store")
        return self

    @property
    def role(self) -> Literal["standalone", "writer", "reader"]:
        """standalone: the in-process KB alone; writer: mirrored to the store; reader: from the store."""
        if self.store is None:
            return "standalone"
        return "reader" if self.writer_url is not None else "writer"

    @field_validator("scene", mode="before")
    @classmethod
    def _scene_path(cls, scene: object) -> object:
        return str(scene) if isinstance(scene, Path) else scene

    @field_validator("cors_origins")
    @classmethod
    def _no_wildcard(cls, origins: list[str]) -> list[str]:
        if "*" in origins:
            raise ValueError("a wildcard CORS origin is not allowed; list the origins explicitly")
        return origins

    @field_validator("token")
    @classmethod
    def _non_empty_token(cls, token: SecretStr | None) -> SecretStr | None:
        if token is not None and not token.get_secret_value().strip():
            return None
        return token


class SettingsError(ValueError):
    """A config file or setting value that cannot be used; the message says which and why."""


def read_config_file(path: Path) -> dict[str, Any]:
    """The settings in a ``.toml`` or ``.json`` file, as a dict."""
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise SettingsError(f"cannot read config file {str(path)!r}: {exc.strerror}") from exc
    try:
        if path.suffix.lower() == ".json":
            data = json.loads(raw)
        elif path.suffix.lower() == ".toml":
            data = tomllib.loads(raw.decode("utf-8"))
        else:
            raise SettingsError(f"config file {str(path)!r} must end in .toml or .json")
    except (json.JSONDecodeError, tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise SettingsError(f"config file {str(path)!r} is not valid: {exc}") from exc
    if not isinstance(data, dict):
        raise SettingsError(f"config file {str(path)!r} must hold an object of settings")
    return data


def _merge(base: dict[str, Any], top: dict[str, Any]) -> dict[str, Any]:
    merged = dict(base)
    for key, value in top.items():
        if isinstance(value, dict) and isinstance(merged.get(key), dict):
            merged[key] = _merge(merged[key], value)
        else:
            merged[key] = value
    return merged


def load_settings(config: Path | None = None, **overrides: Any) -> Settings:
    """Settings from defaults, the config file (``config`` or ``$SITUATED_CONFIG``), the env and
    ``overrides`` (None values are ignored, so CLI options left unset do not override)."""
    path = config or (Path(os.environ[CONFIG_ENV]) if os.environ.get(CONFIG_ENV) else None)
    from_file = read_config_file(path) if path is not None else {}
    explicit = {k: v for k, v in overrides.items() if v is not None}
    try:
        from_env = Settings().model_dump(exclude_unset=True)
        return Settings(**_merge(_merge(from_file, from_env), explicit))
    except ValidationError as exc:
        problems = "; ".join(f"{'.'.join(map(str, e['loc'])) or 'settings'}: {e['msg']}"
                             for e in exc.errors())
        raise SettingsError(f"invalid settings: {problems}") from exc
