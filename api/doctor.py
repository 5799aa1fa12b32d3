"""`situated doctor`: check what a setup needs, say what is wrong and how to fix it.

Each check is a function from the settings to a `Finding` (ok, warn or fail, what was seen, the
fix). Nothing is changed: the KB is built in memory, the data directory gets one temporary file
that is removed, the port is bound and released. The model backend gets one real request: a turn's
prompt for an HTTP backend, one tiny completion in the worker process for `llamacpp:` (which also
says which build to install when llama.cpp crashes).
"""

from __future__ import annotations

import asyncio
import errno
import socket
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

from api.guides import CHECK_KINDS, guide
from api.settings import Settings
from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.llm.base import ChatModel, ChatRequest, ModelError
from dialogue.llm.spec import SpecError, parse_spec
from kb import KB, KbError
from scene.world import load_any_scene

Status = Literal["ok", "warn", "fail"]
#: Where the browser tests look for Chromium (tests/e2e/conftest.py).
CHROMIUM = Path("/usr/bin/chromium")
SPEAKER = "person_doctor"


@dataclass(frozen=True)
class Finding:
    check: str
    status: Status
    detail: str
    fix: str = ""


@dataclass
class Doctor:
    """What the checks look at. `model` replaces the one `settings.llm` names (tests, embedding)."""

    settings: Settings
    model: ChatModel | None = None
    model_timeout: float = 60.0
    chromium: Path = CHROMIUM
    kb: KB | None = field(default=None, init=False)

    def run(self) -> list[Finding]:
        try:
            return [check(self) for check in CHECKS]
        finally:
            if self.kb is not None:
                self.kb.close()


# --- the checks ---------------------------------------------------------------------------------------


def check_kb(doctor: Doctor) -> Finding:
    settings = doctor.settings
    kb = KB()
    doctor.kb = kb
    loaded = []
    try:
        for path in settings.ontology_files:
            kb.load(str(path))
            loaded.append(path.name)
        scene = settings.scene if settings.scene not in (None, "", "none") else None
        said = load_any_scene(kb, scene) if scene is not None else "no scene"
    except (KbError, OSError, ValueError) as exc:
        return Finding("kb", "fail", f"the KB does not load: {exc}",
                       "fix or remove the ontology file or scene named in the settings (--scene, "
                       "SITUATED_ONTOLOGY_FILES, the config file)")
    extra = f", ontology files {', '.join(loaded)}" if loaded else ""
    return Finding("kb", "ok", f"{kb.size()} triples; {said}{extra}")


def check_data_dir(doctor: Doctor) -> Finding:
    folder = doctor.settings.data_dir
    if folder is None:
        return Finding("data", "ok", "no data directory: the KB lives in memory (writes are not kept)")
    existing = folder
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        return Finding("data", "fail", f"{existing} is not a directory, so {folder} cannot be one",
                       f"choose another data directory (--data) or move {existing} away")
    try:
        with tempfile.NamedTemporaryFile(dir=existing, prefix=".situated-doctor-"):
            pass
    except OSError as exc:
        return Finding("data", "fail", f"{existing} is not writable: {exc.strerror}",
                       f"make {existing} writable by this user or choose another data directory (--data)")
    if existing != folder:
        return Finding("data", "ok", f"{folder} does not exist yet; it will be created in {existing}")
    return Finding("data", "ok", f"{folder} is writable")


def check_model(doctor: Doctor) -> Finding:
    spec = doctor.settings.llm
    model = doctor.model
    if model is None:
        try:
            model = parse_spec(spec).model
        except SpecError as exc:
            return Finding("model", "fail", str(exc), "give --llm a valid spec (see situated serve -h)")
    return asyncio.run(_ask(doctor, model, owned=doctor.model is None))


async def _ask(doctor: Doctor, model: ChatModel, owned: bool) -> Finding:
    try:
        return await _check(doctor, model)
    finally:
        if owned:  # its HTTP client or worker process
            await model.aclose()


async def _check(doctor: Doctor, model: ChatModel) -> Finding:
    llm = model.llm  # behind the rules in a hybrid model: that is the one to check
    if llm is None:
        return Finding("model", "ok", f"{model.name}: the offline parser (no model server)")
    started = time.monotonic()
    own = await llm.self_check(doctor.model_timeout)
    if own is not None:
        return Finding("model", "ok" if own.ok else "fail", own.detail, "" if own.ok else own.fix)
    request = await asyncio.to_thread(_turn_request, doctor, llm)
    try:
        result = await llm.chat(request, doctor.model_timeout)
    except ModelError as exc:
        return Finding("model", "fail", f"{llm.name}: {exc}", llm.setup_hint)
    return Finding("model", "ok", f"{llm.name} answered a turn ({len(result.content)} characters) in "
                                  f"{time.monotonic() - started:.1f} s")


def _turn_request(doctor: Doctor, model: ChatModel) -> ChatRequest:
    """The request a real turn sends: the scene's prompt and schema."""
    kb = doctor.kb if doctor.kb is not None else KB()
    doctor.kb = kb
    engine = DialogueEngine(kb, model, EngineConfig(deadline=doctor.model_timeout))
    turn = engine.prepare(engine.ground(), "what do you see?", SPEAKER, (), None)
    schema = engine.schema_for(turn.context.snapshot, SPEAKER)
    return ChatRequest(engine.prompts.messages(turn.context), schema, turn.context)


def check_chromium(doctor: Doctor) -> Finding:
    if doctor.chromium.is_file():
        return Finding("chromium", "ok", f"{doctor.chromium} (for the browser tests)")
    return Finding("chromium", "warn", f"no Chromium at {doctor.chromium}: the browser tests will be skipped "
                                       "(the service does not need it)", "apt-get install chromium")


def check_port(doctor: Doctor) -> Finding:
    host, port = doctor.settings.host, doctor.settings.port
    try:
        family = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0][0]
    except socket.gaierror as exc:
        return Finding("port", "fail", f"cannot resolve host {host!r}: {exc}", "give --host an address")
    with socket.socket(family, socket.SOCK_STREAM) as sock:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as uvicorn does
        try:
            sock.bind((host, port))
        except OSError as exc:
            in_use = exc.errno == errno.EADDRINUSE
            what = "is in use (another situated?)" if in_use else f"cannot be bound: {exc.strerror}"
            return Finding("port", "fail", f"{host}:{port} {what}",
                           "stop what listens there or serve on another port (--port N)")
    return Finding("port", "ok", f"{host}:{port} is free")


CHECKS: tuple[Callable[[Doctor], Finding], ...] = (
    check_kb, check_data_dir, check_model, check_chromium, check_port,
)


# --- the report -----------------------------------------------------------------------------------------


def render(findings: list[Finding]) -> str:
    width = max(len(f.check) for f in findings)
    lines = []
    for f in findings:
        lines.append(f"{f.status.upper():<4}  {f.check:<{width}}  {f.detail}")
        if f.fix and f.status != "ok":
            lines.append(f"{'':<4}  {'':<{width}}  fix: {f.fix}")
        if f.status != "ok" and f.check in CHECK_KINDS:
            lines.append(f"{'':<4}  {'':<{width}}  see: {guide(CHECK_KINDS[f.check])}")
    return "\n".join(lines)


def exit_status(findings: list[Finding], strict: bool = False) -> int:
    """1 when a check failed (or, with `strict`, warned), else 0."""
    bad = {"fail", "warn"} if strict else {"fail"}
    return int(any(f.status in bad for f in findings))
