"""Does this llama-cpp-python build run on this CPU? One tiny completion in a worker process, and a
clear account when it does not: the build's CPU features, the CPU's, and how to reinstall portably.

llama.cpp's default build compiles for the build machine (`-march=native`) and, on x86-64, kernels
for AVX-512 and AMX; on some CPUs (Xeons with AVX-512 and AMX in VMs) every completion then
segfaults. The portable build below runs on every x86-64 CPU with AVX2 (CI builds the same).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

from dialogue.llm.base import ChatResult, ModelError
from dialogue.llm.worker import WorkerCrashed

#: Keep in step with .ci/run.
LLAMA_CPP_VERSION = "0.3.36"
PORTABLE_CMAKE_ARGS = (
    "-DLLAVA_BUILD=OFF -DGGML_NATIVE=OFF -DGGML_AVX=ON -DGGML_AVX2=ON -DGGML_FMA=ON -DGGML_F16C=ON"
)
REINSTALL = (
    f'CMAKE_ARGS="{PORTABLE_CMAKE_ARGS}" pip install --force-reinstall --no-cache-dir --no-deps '
    f"llama-cpp-python=={LLAMA_CPP_VERSION}"
)
#: The CPU flags that decide which llama.cpp kernels can run.
_RELEVANT_FLAG = re.compile(r"^(avx\w*|amx\w*|fma|f16c|sse4_2)$")
#: A tiny answer: the probe checks that generation runs, not what the model says.
PROBE_MESSAGES = [{"role": "user", "content": 'Answer {"ok": true}.'}]
PROBE_SCHEMA: dict[str, Any] = {
    "type": "object", "properties": {"ok": {"type": "boolean"}}, "required": ["ok"]}


def cpu_flags(cpuinfo: Path = Path("/proc/cpuinfo")) -> list[str]:
    """The CPU's SIMD flags that matter to llama.cpp (Linux; empty where /proc/cpuinfo is absent)."""
    try:
        text = cpuinfo.read_text()
    except OSError:
        return []
    for line in text.splitlines():
        key, _, value = line.partition(":")
        if key.strip() == "flags":
            return sorted(flag for flag in value.split() if _RELEVANT_FLAG.match(flag))
    return []


class LocalModel(Protocol):
    """What the check asks of a local model (dialogue.llm.llamacpp's, which checks its own build with
    this module: it is not imported here)."""

    @property
    def name(self) -> str: ...

    async def build_info(self) -> str: ...

    async def complete(
        self, messages: list[dict[str, str]], schema: dict[str, Any], timeout: float
    ) -> ChatResult: ...


@dataclass(frozen=True)
class BuildCheck:
    ok: bool
    #: What happened, and when not ok, what the build and the CPU have and how to fix it.
    message: str
    build: str
    #: The worker died (a build this CPU cannot run): the fix is the portable reinstall.
    crashed: bool = False


async def check_build(model: LocalModel, timeout: float = 120.0) -> BuildCheck:
    """Ask `model`'s worker for its build's CPU features, then for one tiny completion."""
    try:
        build = await model.build_info()
    except ModelError as exc:
        build = f"unknown ({exc})"
    try:
        result = await model.complete(PROBE_MESSAGES, PROBE_SCHEMA, timeout)
    except WorkerCrashed as exc:
        return BuildCheck(False, _crash_report(str(exc), build), build, crashed=True)
    except ModelError as exc:
        return BuildCheck(False, f"{model.name} did not complete: {exc}", build)
    return BuildCheck(True, f"{model.name} answered {result.content.strip()[:60]!r}", build)


def _crash_report(error: str, build: str) -> str:
    flags = " ".join(cpu_flags()) or "unknown"
    return (
        f"llama.cpp crashed: {error}. Its build uses: {build}. This CPU has: {flags}. A build for another "
        "CPU, or llama.cpp's AVX-512/AMX kernels on a CPU (or VM) that cannot run them, crash like this; "
        f"reinstall llama-cpp-python portably: {REINSTALL}"
    )
