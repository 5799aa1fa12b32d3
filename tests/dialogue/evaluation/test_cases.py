import json
from pathlib import Path

import pytest

from dialogue.engine import TurnResult
from dialogue.evaluation.cases import EvalError, check, format_report, load_cases, run
from dialogue.evaluation.command import main
from dialogue.intents import BRING_OBJECT, GRAB_OBJECT, SAY, make_intent, raw_user_input
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.openai import OpenAIModel
from dialogue.llm.testing import ScriptedModel
from tests.dialogue.conftest import EVAL_DIR
from tests.dialogue.llm.fakeserver import fake_server
from tests.dialogue.llm.test_openai import reply as openai_reply

#: Every set the rules are measured on in this repository (tests/dialogue/eval/: the shared development
#: set's copy and the sets written without sight of the parser, each tuned on after its first run).
EVAL_SETS = sorted(EVAL_DIR.glob("*.jsonl"))


@pytest.mark.parametrize("path", EVAL_SETS, ids=lambda p: p.stem)
def test_every_set_keeps_the_rules_claims_right_and_its_score(path: Path) -> None:
    """Issue 29: a wrong claim is the worst outcome (the robot acts on the wrong thing), so every set
    keeps the precision of the rules' claims at 0.97 or more, and its score at 0.90 or more."""
    report = run(path, "rules")
    wrong = [(r.case.id, r.problems) for r in report.claims if not r.passed]
    assert report.claim_precision is not None and report.claim_precision >= 0.97, wrong
    assert report.score >= 0.90, [(r.case.id, r.problems) for r in report.results if not r.passed]


def test_the_measured_sets_are_all_there() -> None:
    assert len(EVAL_SETS) >= 14 and {"dev", "extra", "multi"} <= {p.stem for p in EVAL_SETS}
    assert sum(len(load_cases(p)) for p in EVAL_SETS) >= 1_450


def test_main_prints_table_and_one_json_line(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    cases = tmp_path / "cases.jsonl"
    (tmp_path / "scenes").mkdir()
    (tmp_path / "scenes" / "kitchen.txt").write_text((EVAL_DIR / "scenes" / "kitchen.txt").read_text())
    cases.write_text(
        json.dumps(
            {
                "id": "a",
                "scene": "kitchen",
                "speaker": "person_alice",
                "input": "grab the cup",
                "expect": {"intent": GRAB_OBJECT, "roles": {"object": "cup_1"}},
            }
        )
        + "\n"
        + json.dumps(
            {
                "id": "b",
                "scene": "kitchen",
                "input": "grab the cup",
                "expect": {"intent": GRAB_OBJECT, "roles": {"object": "apple_1"}},
            }
        )
        + "\n"
    )
    assert main([str(cases), "--json"]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    summary = json.loads(out[-1])
    assert summary == {
        "total": 2,
        "passed": 1,
        "score": 0.5,
        "rules_claims": {"claimed": 2, "right": 1, "precision": 0.5},
        "by_intent": {GRAB_OBJECT: {"total": 2, "passed": 1, "score": 0.5}},
        "failures": ["b"],
    }
    assert any("role object: expected 'apple_1', got 'cup_1'" in line for line in out)


def test_bad_files_give_clear_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"id": "x", "input": "hi"}\n')
    with pytest.raises(EvalError, match=r"bad\.jsonl:1: 'expect' must be an object"):
        load_cases(bad)
    bad.write_text('{"id": "x", "input": "hi", "scene": "nowhere", "expect": {"intent": null}}\n')
    assert main([str(bad)]) == 2
    assert "scene 'nowhere' not found" in capsys.readouterr().err
    assert main([str(tmp_path / "missing.jsonl")]) == 2
    bad.write_text("not json\n")
    with pytest.raises(EvalError, match="not JSON"):
        load_cases(bad)


def test_check_rules() -> None:
    case = load_cases(EVAL_DIR / "dev.jsonl")[15]  # tell Tom that lunch is ready
    say = make_intent(SAY, {"object": "Lunch is ready!", "recipient": "person_tom"}, source="p", confidence=1)
    assert check(case, TurnResult("ok", (say,))) == []
    assert check(case, TurnResult("ok", ())) != []
    clarify = next(c for c in load_cases(EVAL_DIR / "dev.jsonl") if c.expect.get("clarify"))
    raw = raw_user_input("x", source="p")
    assert check(clarify, TurnResult("Which one?", (raw,))) == []
    assert check(clarify, TurnResult("Which one.", ())) == ["expected a clarifying question and no intent"]


def write_cases(tmp_path: Path, *cases: dict[str, object]) -> Path:
    (tmp_path / "scenes").mkdir(exist_ok=True)
    (tmp_path / "scenes" / "kitchen.txt").write_text((EVAL_DIR / "scenes" / "kitchen.txt").read_text())
    path = tmp_path / "cases.jsonl"
    path.write_text("".join(json.dumps({"scene": "kitchen", "speaker": "person_alice", **c}) + "\n" for c in cases))
    return path


GRAB_CUP = {"id": "right", "input": "grab the cup", "expect": {"intent": GRAB_OBJECT, "roles": {"object": "cup_1"}}}
WRONG = {"id": "wrong", "input": "grab the cup", "expect": {"intent": GRAB_OBJECT, "roles": {"object": "apple_1"}}}
WEATHER = {"id": "weather", "input": "how is the weather today?", "expect": {"intent": None}}


def test_rules_claims_are_the_turns_the_rules_answered(tmp_path: Path) -> None:
    report = run(write_cases(tmp_path, GRAB_CUP, WRONG, WEATHER), "rules")
    # The weather is not understood (a pass: no intent expected, none given) and so is no claim.
    assert report.passed == 2 and [r.case.id for r in report.claims] == ["right", "wrong"]
    assert report.claim_precision == 0.5
    assert report.summary()["rules_claims"] == {"claimed": 2, "right": 1, "precision": 0.5}
    (overall,) = [line for line in format_report(report).splitlines() if line.startswith("all ")]
    assert overall.split()[1:4] == ["2", "3", "0.67"] and overall.endswith("rules' claims: 1/2 right (precision 0.50)")


def test_a_reading_the_rules_only_propose_is_no_claim(tmp_path: Path) -> None:
    dance = {"id": "dance", "input": "can you dance?", "expect": {"intent": "__intent_perform_motion__"}}
    report = run(write_cases(tmp_path, GRAB_CUP, dance), "rules")
    (proposed,) = [r for r in report.results if r.case.id == "dance"]
    assert proposed.result.confirm and proposed.result.response == "Shall I dance?" and not proposed.passed
    assert [r.case.id for r in report.claims] == ["right"] and report.claim_precision == 1.0


def test_turns_the_model_answered_behind_the_rules_are_not_claims(tmp_path: Path) -> None:
    model = HybridModel(ScriptedModel([{"verbal_ack": "It is sunny.", "user_intent": None}]))
    report = run(write_cases(tmp_path, GRAB_CUP, WEATHER), model=model)
    assert report.passed == 2 and [r.case.id for r in report.claims] == ["right"]
    assert report.claim_precision == 1.0


def test_a_model_alone_makes_no_claims(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    model = ScriptedModel([{"verbal_ack": "It is sunny.", "user_intent": None}])
    report = run(write_cases(tmp_path, WEATHER), model=model)
    assert report.passed == 1 and report.claims == [] and report.claim_precision is None
    assert report.summary()["rules_claims"] == {"claimed": 0, "right": 0, "precision": None}
    assert "rules' claims: none" in format_report(report)


def test_a_set_runs_on_one_client_closed_at_the_end(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    closed: list[str] = []
    close = OpenAIModel.aclose

    async def recorded(self: OpenAIModel) -> None:
        closed.append(self.name)
        await close(self)

    monkeypatch.setattr(OpenAIModel, "aclose", recorded)
    sunny = openai_reply(json.dumps({"verbal_ack": "It is sunny.", "user_intent": None}))
    with fake_server(keep_alive=True) as server:
        server.replies.extend([(200, sunny)] * 2)
        cases = write_cases(tmp_path, WEATHER, {**WEATHER, "id": "again"})
        report = run(cases, f"hybrid:openai:m@{server.url}/v1")
    assert report.passed == 2 and report.claims == []
    assert len(server.peers) == 2 and len(set(server.peers)) == 1
    assert closed == [f"openai:m@{server.url}/v1"]


def test_compound_commands_return_every_intent_in_order() -> None:
    report = run(EVAL_DIR / "multi.jsonl", "rules")
    assert report.total >= 20
    assert report.score == 1.0, [(r.case.id, r.problems) for r in report.results if not r.passed]


def test_then_checks_the_following_intents_in_order(tmp_path: Path) -> None:
    line = {
        "id": "x", "input": "take the cup and give it to Tom",
        "expect": {"intent": GRAB_OBJECT, "roles": {"object": "cup_1"},
                   "then": [{"intent": BRING_OBJECT, "roles": {"object": "cup_1", "recipient": "person_tom"}}]},
    }  # fmt: skip
    (tmp_path / "c.jsonl").write_text(json.dumps(line))
    case = load_cases(tmp_path / "c.jsonl")[0]
    grab = make_intent(GRAB_OBJECT, {"object": "cup_1"}, source="p", confidence=1)
    bring = make_intent(BRING_OBJECT, {"object": "cup_1", "recipient": "person_tom"}, source="p", confidence=1)
    to_ann = make_intent(BRING_OBJECT, {"object": "cup_1", "recipient": "person_ann"}, source="p", confidence=1)
    assert check(case, TurnResult("ok", (grab, bring))) == []
    assert check(case, TurnResult("ok", (grab,))) == [f"expected {GRAB_OBJECT}, {BRING_OBJECT}, got {GRAB_OBJECT}"]
    assert check(case, TurnResult("ok", (bring, grab))) != []
    assert check(case, TurnResult("ok", (grab, bring, grab))) != []  # nothing else may follow
    assert check(case, TurnResult("ok", (grab, to_ann))) == [
        "intent 2 role recipient: expected 'person_tom', got 'person_ann'"
    ]
    line["expect"]["then"] = [{"intent": 3}]  # type: ignore[index]
    (tmp_path / "c.jsonl").write_text(json.dumps(line))
    with pytest.raises(EvalError, match=r"expect\.then"):
        load_cases(tmp_path / "c.jsonl")
