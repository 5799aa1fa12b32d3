"""Errors and help of the situated command name the guide that explains them, from one table."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from api.cli import main
from api.client import ClientError
from api.guides import GUIDES, Guided, Kind, about, kind_of, see
from api.settings import SettingsError
from dialogue.llm.spec import SpecError
from kb.errors import KbError

REPO = Path(__file__).parents[2]


def test_the_help_lists_every_guide() -> None:
    assert set(GUIDES) == set(Kind)
    done = subprocess.run([sys.executable, "-m", "api.cli", "--help"], capture_output=True, text=True,
                          check=True, cwd=REPO)
    for kind in Kind:
        assert f"docs/{kind.value}" in done.stdout


def test_the_kind_is_the_cause_s_when_the_cause_is_more_specific() -> None:
    try:
        try:
            raise SpecError("bad backend spec 'bogus'")
        except SpecError as exc:
            raise SettingsError(f"llm: {exc}") from exc
    except SettingsError as wrapped:
        assert kind_of(wrapped) is Kind.MODELS
    assert kind_of(SettingsError("port: too large")) is Kind.SETUP
    assert kind_of(ClientError(401, "unauthorized", "a token is needed")) is Kind.SECURITY
    assert kind_of(ClientError(503, "service_unavailable", "cannot be reached")) is Kind.SETUP
    assert see(ValueError("not ours")) == ""


def test_what_a_command_was_reading_decides_a_kb_error_s_kind() -> None:
    with pytest.raises(Guided) as raised, about(Kind.SCENES):
        raise KbError("cannot read scene 'x.svg'")
    assert kind_of(raised.value) is Kind.SCENES and str(raised.value) == "cannot read scene 'x.svg'"
    with pytest.raises(ValueError), about(Kind.SCENES):  # only the errors named are of the kind
        raise ValueError("a bug")


@pytest.mark.parametrize(("words", "guide"), [
    (["chat", "--scene", "none", "--llm", "bogus:x", "--say", "hi"], "docs/models.md"),
    (["kb", "query", "?x isOn ?y", "--scene", "missing.svg"], "docs/scenes.md"),
    (["kb", "query", "?x isOn ?y", "--scene", "none", "--ontology", "missing.ttl"], "docs/scenes.md"),
    (["kb", "query", "?x", "--scene", "none"], "docs/knowledge-base.md"),
    (["chat", "--scene", "none", "--ask", "How old are you?", "--say", "hi"], "docs/chatbot.md"),
    (["ros", "env", "--prefix", "no-such-prefix"], "docs/ros.md"),
    (["eval", "missing.jsonl"], "docs/evaluation.md"),
    (["kb", "add", "cup_1 isOn table_1", "--scene", "none"], "docs/knowledge-base.md"),
    (["serve", "--data", "/dev/null/data"], "docs/knowledge-base.md"),
])
def test_an_error_names_the_guide_that_explains_it(words: list[str], guide: str, tmp_path: Path,
                                                   monkeypatch: pytest.MonkeyPatch,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(words) == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert last.endswith(f"(see {guide})"), last


def test_a_doctor_finding_that_is_not_ok_names_its_guide() -> None:
    from api.doctor import CHECKS, Finding, render

    assert {check.__name__.removeprefix("check_").replace("data_dir", "data") for check in CHECKS} == {
        "kb", "data", "model", "chromium", "port"}
    text = render([Finding("model", "fail", "ollama: connection refused", "start ollama"),
                   Finding("port", "ok", "127.0.0.1:8000 is free")])
    assert "see: docs/models.md" in text and "docs/getting-started.md" not in text
