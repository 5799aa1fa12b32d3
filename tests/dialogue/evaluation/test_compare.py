import json
import shutil
from pathlib import Path

import pytest

from dialogue.evaluation.command import main
from dialogue.evaluation.compare import (
    TUTORIAL_INTENTS,
    TUTORIAL_SCHEMA,
    compare,
    environment_lines,
    format_comparison,
    tutorial_result,
)
from dialogue.intents import GRAB_OBJECT, GREET
from dialogue.llm.base import ChatRequest
from dialogue.llm.spec import Backend
from dialogue.llm.testing import FunctionModel
from tests.dialogue.conftest import EVAL_DIR, scene_kb

CASES = ("kitchen-greet-hello", "kitchen-grab-class", "kitchen-say-tell-that")


@pytest.fixture
def cases(tmp_path: Path) -> Path:
    lines = [line for line in (EVAL_DIR / "dev.jsonl").read_text().splitlines() if json.loads(line)["id"] in CASES]
    path = tmp_path / "cases.jsonl"
    path.write_text("\n".join(lines) + "\n")
    shutil.copytree(EVAL_DIR / "scenes", tmp_path / "scenes")
    return path


def test_environment_lines_follow_the_tutorial() -> None:
    kb = scene_kb("kitchen")
    try:
        lines = environment_lines(kb)
    finally:
        kb.close()
    assert "- I see a cup labeled cup_1." in lines
    assert "- I see a artifact labeled sponge." in lines
    assert len(lines) == 8  # one per `myself sees` object, people and places included


def test_tutorial_schema_has_free_text_roles_and_eight_types() -> None:
    intent = TUTORIAL_SCHEMA["$defs"]["TutorialIntent"]
    assert intent["properties"]["type"]["enum"] == list(TUTORIAL_INTENTS) and len(TUTORIAL_INTENTS) == 8
    assert {"type": "string"} in intent["properties"]["object"]["anyOf"]
    assert sorted(intent["required"]) == ["goal", "input", "object", "recipient", "type"]


def test_tutorial_mapping_is_verbatim() -> None:
    content = json.dumps(
        {
            "verbal_ack": "Sure",
            "user_intent": {"type": GRAB_OBJECT, "object": "the red cup", "recipient": None, "input": None, "goal": None},
        }
    )
    result = tutorial_result(content)
    assert result.response == "Sure"
    (intent,) = result.intents
    assert intent.data == {"type": GRAB_OBJECT, "object": "the red cup"} and intent.priority == 0
    assert tutorial_result('{"verbal_ack": "hi"}').error_msg.startswith("invalid answer")
    stop = {"type": "__intent_stop_activity__", "object": None, "recipient": None, "input": None, "goal": None}
    assert tutorial_result(json.dumps({"verbal_ack": None, "user_intent": stop})).intents == ()


def test_compare_counts_what_resolution_fixes(cases: Path) -> None:
    """A model naming things by words: the tutorial passes them on, the engine resolves them."""

    def answer(request: ChatRequest) -> dict[str, object]:
        text = request.context.text.lower()
        kind, obj, recipient = (GREET, None, "Alice") if "hello" in text else (GRAB_OBJECT, "cup", None)
        return {
            "verbal_ack": "OK",
            "user_intent": {"type": kind, "object": obj, "recipient": recipient, "input": None, "goal": None},
        }

    model = FunctionModel(answer, name="words")
    comparison = compare(cases, "words", backend=Backend(model, "words"))
    tutorial, situated = comparison.tutorial, comparison.situated
    assert (tutorial.report.passed, tutorial.ungrounded, tutorial.referents) == (0, 3, 3)
    assert situated.ungrounded == 0
    assert {r.case.id for r in situated.report.results if r.passed} == {"kitchen-greet-hello", "kitchen-grab-class"}
    assert any(r.schema is TUTORIAL_SCHEMA for r in model.requests)
    table = format_comparison(comparison)
    assert "ungrounded referents" in table and "3/3" in table


def test_main_compare_with_rules_offline(cases: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["--compare", str(cases), "--json"]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    summary = json.loads(out[-1])
    assert summary["llm"] == "rules"
    assert summary["situated"]["passed"] == 3 and summary["situated"]["ungrounded"] == 0
    # The rules put SAY text in `input`; taken verbatim, the tutorial mapping has no `object`.
    assert summary["tutorial"]["failures"] == ["kitchen-say-tell-that"]
    assert {"referents", "ungrounded", "errors", "seconds"} <= set(summary["tutorial"])
    assert out[0] == "comparison with rules on 3 cases"


def test_main_compare_argument_errors(cases: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main([str(cases), "--compare", str(cases)])
    with pytest.raises(SystemExit):
        main([str(cases), "--hybrid"])
    assert main(["--compare", str(cases), "--llm", "nope"]) == 2
    assert "bad backend spec 'nope'" in capsys.readouterr().err


def test_hybrid_runs_the_rules_first_on_the_engine_side_only(cases: Path) -> None:
    def answer(request: ChatRequest) -> dict[str, object]:
        return {"verbal_ack": "OK", "user_intent": None}

    model = FunctionModel(answer, name="words")
    comparison = compare(cases, "words", backend=Backend(model, "words"), hybrid=True)
    assert comparison.llm == "words --hybrid"
    # The tutorial asked the model for every case; the engine's rules understood all three.
    assert len(model.requests) == 3 and all(r.schema is TUTORIAL_SCHEMA for r in model.requests)
    assert {r.result.backend for r in comparison.situated.report.results} == {"rules"}
    assert comparison.situated.report.claims_summary() == {"claimed": 3, "right": 3, "precision": 1.0}
    row = next(line for line in format_comparison(comparison).splitlines() if line.startswith("rules claims right"))
    assert row.split()[3:] == ["-", "3/3", "1.00"]
