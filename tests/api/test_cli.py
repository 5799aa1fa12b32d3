"""The situated command: help, kb and humans in-process and against a running service, chat, eval
and bench delegation."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from api.cli import main
from tests.api.conftest import SCENE, Live

COMMANDS = ("serve", "chat", "kb", "humans", "eval", "bench")


def test_help_documents_every_command() -> None:
    done = subprocess.run([sys.executable, "-m", "api.cli", "--help"], capture_output=True, text=True,
                          check=True, cwd=Path(__file__).parents[2])
    for command in COMMANDS:
        assert f"    {command} " in done.stdout
    assert "situated kb query" in done.stdout


def test_kb_query_in_process(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["kb", "query", "myself sees ?o", "?o rdf:type dbr:Cup", "--scene", str(SCENE)]) == 0
    assert json.loads(capsys.readouterr().out) == [{"o": "cup_1"}]
    assert main(["kb", "lookup", "cookbook", "--scene", str(SCENE)]) == 0
    assert json.loads(capsys.readouterr().out) == [["book_1", "instance"]]


def test_kb_errors_are_reported_not_raised(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["kb", "query", "myself sees"]) == 2
    assert "situated kb:" in capsys.readouterr().err


def test_kb_and_humans_against_a_running_service(live: Live, capsys: pytest.CaptureFixture[str]) -> None:
    url = ["--url", live.url]
    assert main(["kb", "add", "person_bob rdf:type Human", "person_bob rdfs:label \"Bob\"", *url]) == 0
    assert main(["kb", "retract", "myself sees person_alice", *url]) == 0
    capsys.readouterr()
    assert main(["kb", "query", "?p rdfs:label \"Bob\"", *url]) == 0
    assert json.loads(capsys.readouterr().out) == [{"p": "person_bob"}]
    assert main(["kb", "details", "cup_1", *url]) == 0
    assert json.loads(capsys.readouterr().out)["id"] == "cup_1"
    assert main(["humans", *url]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split() == ["id", "name", "seen", "engagement"]
    assert lines[1].split() == ["person_alice", "Alice", "no", "engaged"]
    assert lines[2].split() == ["person_bob", "Bob", "no", "-"]
    assert main(["kb", "query", "?x sees", *url]) == 2
    assert "HTTP 400" in capsys.readouterr().err


def test_chat_in_process_and_remote(live: Live, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["chat", "--scene", str(SCENE), "--user", "person_alice", "--say", "pick up the cup"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("robot: ") and '__intent_grab_object__ {"object": "cup_1"}' in out
    assert main(["chat", "--url", live.url, "--user", "person_alice", "--say", "hello"]) == 0
    assert '__intent_greet__ {"recipient": "person_alice"}' in capsys.readouterr().out


def test_chat_ignores_blank_utterances(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["chat", "--scene", str(SCENE), "--user", "person_alice", "--say", "  ", "--say", "hello"]) == 0
    out = capsys.readouterr().out
    assert out.count("robot: ") == 1 and "__intent_greet__" in out


def test_eval_and_bench_delegate(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as done:
        main(["eval", "--help"])
    assert done.value.code == 0
    assert "situated eval" in capsys.readouterr().out
    status = main(["bench", "http", "--count", "40", "--seconds", "2"])
    out = capsys.readouterr().out
    assert status in (0, 1)  # the verdict depends on the machine; the table must be there
    assert "POST /echo (bare FastAPI)" in out and "POST /kb/query" in out
    assert "POST /dialogues/default/interactions" in out and "target >= 50%" in out
