"""`situated doctor`: each check's success and failure, the report and the exit status."""

from __future__ import annotations

import socket
from functools import partial
from pathlib import Path

import pytest

from api.cli import main
from api.doctor import (
    Doctor,
    Finding,
    check_chromium,
    check_data_dir,
    check_kb,
    check_model,
    check_port,
    exit_status,
    render,
)
from api.settings import Settings
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.llamabuild import PORTABLE_CMAKE_ARGS
from dialogue.llm.llamacpp import LlamaCppModel
from tests.dialogue.llm import fakellama
from tests.dialogue.llm.common import ANSWER
from tests.dialogue.llm.fakellama import FakeControl
from tests.dialogue.llm.fakeserver import fake_server, free_port_url
from tests.dialogue.llm.test_ollama import reply as ollama_reply
from tests.dialogue.llm.test_openai import reply as openai_reply


def doctor(**settings: object) -> Doctor:
    return Doctor(Settings(scene="none", **settings), model_timeout=10.0)  # type: ignore[arg-type]


def run_check(check: object, d: Doctor) -> Finding:
    try:
        return check(d)  # type: ignore[operator, no-any-return]
    finally:
        if d.kb is not None:
            d.kb.close()


# --- kb ---------------------------------------------------------------------------------------------------


def test_kb_loads_with_the_scene() -> None:
    finding = run_check(check_kb, Doctor(Settings(scene="demo")))
    assert finding.status == "ok" and "triples" in finding.detail and "scene entities" in finding.detail


def test_kb_that_does_not_load_names_the_file(tmp_path: Path) -> None:
    bad = tmp_path / "broken.ttl"
    bad.write_text("this is not turtle .")
    finding = run_check(check_kb, doctor(ontology_files=[bad]))
    assert finding.status == "fail" and "does not load" in finding.detail and finding.fix


# --- data directory --------------------------------------------------------------------------------------


def test_data_dir_writable_missing_or_absent(tmp_path: Path) -> None:
    assert run_check(check_data_dir, doctor()).status == "ok"
    ok = run_check(check_data_dir, doctor(data_dir=tmp_path))
    assert ok.status == "ok" and "is writable" in ok.detail
    later = run_check(check_data_dir, doctor(data_dir=tmp_path / "new" / "data"))
    assert later.status == "ok" and "will be created" in later.detail
    assert not (tmp_path / "new").exists() and list(tmp_path.iterdir()) == []  # nothing was left behind


def test_data_dir_that_cannot_be_a_directory(tmp_path: Path) -> None:
    (tmp_path / "afile").write_text("x")
    finding = run_check(check_data_dir, doctor(data_dir=tmp_path / "afile" / "data"))
    assert finding.status == "fail" and "is not a directory" in finding.detail and "--data" in finding.fix


# --- model --------------------------------------------------------------------------------------------------


def test_rules_need_no_server() -> None:
    assert run_check(check_model, doctor(llm="rules")).status == "ok"


def test_bad_spec_fails() -> None:
    finding = run_check(check_model, doctor(llm="nonsense:model"))
    assert finding.status == "fail" and "unknown backend" in finding.detail


def test_ollama_answers_a_real_turn_request() -> None:
    with fake_server() as server:
        server.replies.append((200, ollama_reply(ANSWER)))
        finding = run_check(check_model, doctor(llm=f"ollama:gemma3:1b@{server.url}"))
    assert finding.status == "ok" and "answered a turn" in finding.detail
    path, body = server.requests[0]
    assert path == "/api/chat" and body["format"]["type"] == "object"  # the turn's schema


def test_ollama_down_says_how_to_start_it() -> None:
    finding = run_check(check_model, doctor(llm=f"ollama:gemma3:1b@{free_port_url()}"))
    assert finding.status == "fail" and "unreachable" in finding.detail
    assert "ollama serve" in finding.fix and "ollama pull gemma3:1b" in finding.fix


def test_openai_answers_and_refuses() -> None:
    with fake_server() as server:
        server.replies.append((200, openai_reply(ANSWER)))
        server.replies.append((404, {"error": "model 'qwen' not found"}))
        url = f"{server.url}/v1"
        good = run_check(check_model, doctor(llm=f"openai:qwen@{url}"))
        bad = run_check(check_model, doctor(llm=f"openai:qwen@{url}"))
    assert good.status == "ok" and server.requests[0][0] == "/v1/chat/completions"
    assert bad.status == "fail" and "HTTP 404" in bad.detail and "serving 'qwen'" in bad.fix


def test_hybrid_checks_the_model_behind_the_rules() -> None:
    with fake_server() as server:
        server.replies.append((200, ollama_reply(ANSWER)))
        good = run_check(check_model, doctor(llm=f"hybrid:ollama:gemma3:1b@{server.url}"))
    assert good.status == "ok" and good.detail.startswith(f"ollama:gemma3:1b@{server.url} answered a turn")
    assert server.requests[0][0] == "/api/chat"
    down = run_check(check_model, doctor(llm=f"hybrid:ollama:gemma3:1b@{free_port_url()}"))
    assert down.status == "fail" and "unreachable" in down.detail and "ollama serve" in down.fix


def test_hybrid_llamacpp_completes_in_the_worker(tmp_path: Path) -> None:
    model = fake_llama(tmp_path, answer='{"ok": true}')
    try:
        finding = run_check(check_model, Doctor(Settings(scene="none"), model=HybridModel(model), model_timeout=30.0))
        assert model.worker_pid is not None
    finally:
        model.close()
    assert finding.status == "ok" and "worker process" in finding.detail


def fake_llama(tmp_path: Path, **config: object) -> LlamaCppModel:
    fake = FakeControl(tmp_path)
    fake.set(**config)
    (tmp_path / "m.gguf").write_bytes(b"GGUF")
    return LlamaCppModel(tmp_path / "m.gguf", worker_setup=partial(fakellama.install, str(tmp_path)))


def test_llamacpp_completes_in_the_worker(tmp_path: Path) -> None:
    model = fake_llama(tmp_path, answer='{"ok": true}')
    try:
        d = Doctor(Settings(scene="none"), model=model, model_timeout=30.0)
        finding = run_check(check_model, d)
        assert model.worker_pid is not None  # the completion ran in the worker
    finally:
        model.close()
    assert finding.status == "ok" and "worker process" in finding.detail and "AVX2 = 1" in finding.detail


def test_llamacpp_crash_says_which_build_to_install(tmp_path: Path) -> None:
    model = fake_llama(tmp_path, crash="abort")
    try:
        finding = run_check(check_model, Doctor(Settings(scene="none"), model=model, model_timeout=30.0))
    finally:
        model.close()
    assert finding.status == "fail" and "killed by SIGABRT" in finding.detail and "This CPU has" in finding.detail
    assert PORTABLE_CMAKE_ARGS in finding.fix


# --- chromium and port -----------------------------------------------------------------------------------


def test_chromium_present_or_missing(tmp_path: Path) -> None:
    (tmp_path / "chromium").write_text("")
    d = doctor()
    d.chromium = tmp_path / "chromium"
    assert check_chromium(d).status == "ok"
    d.chromium = tmp_path / "absent"
    missing = check_chromium(d)
    assert missing.status == "warn" and "apt-get install chromium" in missing.fix


def test_port_free_or_in_use() -> None:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        sock.listen()
        port = sock.getsockname()[1]
        busy = check_port(doctor(port=port))
    assert busy.status == "fail" and f"127.0.0.1:{port} is in use" in busy.detail and "--port" in busy.fix
    assert check_port(doctor(port=port)).status == "ok"


# --- report and command ------------------------------------------------------------------------------------


def test_exit_status_and_report() -> None:
    ok, warn, fail = Finding("a", "ok", "fine"), Finding("b", "warn", "meh", "do x"), Finding("c", "fail", "bad", "do y")
    assert exit_status([ok, warn]) == 0 and exit_status([ok, warn], strict=True) == 1
    assert exit_status([ok, fail]) == 1
    text = render([ok, warn, fail])
    assert "OK    a  fine" in text and "FAIL  c  bad" in text and "fix: do y" in text


def test_command_exits_1_on_a_problem_and_0_without(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    assert main(["doctor", "--scene", "none", "--llm", "rules", "--port", str(port)]) == 0
    (tmp_path / "afile").write_text("x")
    assert main(["doctor", "--scene", "none", "--data", str(tmp_path / "afile" / "d"), "--port", str(port)]) == 1
    out = capsys.readouterr().out
    assert "FAIL  data" in out and "fix:" in out
