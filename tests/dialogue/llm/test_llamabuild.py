"""The build probe: a build that crashes on this CPU is reported with its features, the CPU's and the fix."""

from __future__ import annotations

import asyncio
from functools import partial
from pathlib import Path

from dialogue.llm import llamabuild
from dialogue.llm.llamabuild import PORTABLE_CMAKE_ARGS, check_build, cpu_flags
from dialogue.llm.llamacpp import LlamaCppModel
from tests.dialogue.llm import fakellama
from tests.dialogue.llm.fakellama import FakeControl

CPUINFO = """processor\t: 0
flags\t\t: fpu sse4_2 avx avx2 fma f16c avx512f avx512_bf16 amx_tile amx_int8 hypervisor
"""


def probe(tmp_path: Path, **config: object) -> llamabuild.BuildCheck:
    fake = FakeControl(tmp_path)
    fake.set(**config)
    (tmp_path / "m.gguf").write_bytes(b"GGUF")
    model = LlamaCppModel(tmp_path / "m.gguf", worker_setup=partial(fakellama.install, str(tmp_path)))
    try:
        return asyncio.run(check_build(model, timeout=30))
    finally:
        model.close()


def test_cpu_flags_keep_what_decides_the_kernels(tmp_path: Path) -> None:
    (tmp_path / "cpuinfo").write_text(CPUINFO)
    assert cpu_flags(tmp_path / "cpuinfo") == [
        "amx_int8", "amx_tile", "avx", "avx2", "avx512_bf16", "avx512f", "f16c", "fma", "sse4_2"]
    assert cpu_flags(tmp_path / "absent") == []


def test_a_build_that_answers_passes(tmp_path: Path) -> None:
    check = probe(tmp_path, answer='{"ok": true}')
    assert check.ok and "answered" in check.message and "FAKE = 1" in check.build


def test_a_build_that_crashes_says_what_it_uses_and_how_to_reinstall(tmp_path: Path) -> None:
    check = probe(tmp_path, crash="segv")
    assert not check.ok
    assert "killed by SIGSEGV" in check.message and "AVX2 = 1 | FAKE = 1" in check.message
    assert "This CPU has: " in check.message and PORTABLE_CMAKE_ARGS in check.message
    assert "--force-reinstall" in check.message


def test_a_model_error_is_not_called_a_crash(tmp_path: Path) -> None:
    check = probe(tmp_path, load_error="bad magic")
    assert not check.ok and "bad magic" in check.message and "reinstall" not in check.message
