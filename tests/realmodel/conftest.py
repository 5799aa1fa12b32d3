"""Fixtures for the tests that run a real local LLM (SmolLM2-135M-Instruct, the 'local' extra).

They are skipped, with the reason, when llama-cpp-python or the packaged model is missing. Before
any of them runs the model, one tiny completion probes the build in a worker process: a build that
crashes on this CPU fails them with its CPU features, the CPU's and the portable reinstall command,
instead of killing pytest. One model instance and one `llama_cpp.server` serve the whole session.
They check plumbing, not accuracy.
"""

from __future__ import annotations

import asyncio
import importlib.util
import os
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

from bench.oxigraph import free_port
from dialogue.llm.llamabuild import BuildCheck, check_build
from dialogue.llm.llamacpp import INSTALL_HINT, LlamaCppModel, LocalModelUnavailable, smollm2_path

SERVER_START_TIMEOUT = 60.0


def missing_reason() -> str | None:
    if importlib.util.find_spec("llama_cpp") is None:
        return f"llama-cpp-python is not installed ({INSTALL_HINT})"
    try:
        smollm2_path()
    except LocalModelUnavailable as exc:
        return str(exc)
    return None


MISSING = missing_reason()


#: Every module here starts with `pytestmark = REALMODEL`.
REALMODEL = [
    pytest.mark.realmodel,
    pytest.mark.skipif(MISSING is not None, reason=f"real-model test skipped: {MISSING}"),
]


@pytest.fixture(scope="session")
def model_path() -> Path:
    return smollm2_path()


@pytest.fixture(scope="session")
def llama_build(model_path: Path) -> BuildCheck:
    """One tiny completion in a throwaway worker process: does this build run on this CPU?"""
    probe = LlamaCppModel(model_path, label="smollm2")
    try:
        check = asyncio.run(check_build(probe))
    finally:
        probe.close()
    if not check.ok:
        pytest.fail(f"the llama.cpp build cannot run the model here: {check.message}", pytrace=False)
    return check


@pytest.fixture(scope="session")
def local_model(model_path: Path, llama_build: BuildCheck) -> Iterator[LlamaCppModel]:
    model = LlamaCppModel(model_path, label="smollm2")
    model.load()
    yield model
    model.close()


@pytest.fixture(scope="session")
def llama_server(
    model_path: Path, llama_build: BuildCheck, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[str]:
    """A `llama_cpp.server` on a free loopback port; yields its OpenAI base URL."""
    port = free_port()
    log = tmp_path_factory.mktemp("llama_server") / "server.log"
    command = [
        sys.executable, "-m", "llama_cpp.server", "--model", str(model_path), "--host", "127.0.0.1",
        "--port", str(port), "--n_ctx", "2048", "--n_threads", "1", "--n_threads_batch", "1",
        "--logits_all", "false", "--verbose", "false",
    ]  # fmt: skip
    with log.open("wb") as out:
        process = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT, env={**os.environ})
    base_url = f"http://127.0.0.1:{port}/v1"
    try:
        started = time.monotonic()
        while True:
            if process.poll() is not None:
                pytest.fail(f"llama_cpp.server exited with {process.returncode}: {log.read_text()[-2000:]}")
            try:
                if httpx.get(f"{base_url}/models", timeout=1.0).status_code == 200:
                    break
            except httpx.HTTPError:
                pass
            if time.monotonic() - started > SERVER_START_TIMEOUT:
                pytest.fail(f"llama_cpp.server not ready after {SERVER_START_TIMEOUT:g} s: {log.read_text()[-2000:]}")
            time.sleep(0.25)
        yield base_url
    finally:
        process.terminate()
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
