"""Run dialogue evaluation cases (the format of eval/README.md) and score them per intent.

Each case gets a fresh KB: the default ontology, the case's scene (`scenes/<name>.txt` next to the
cases file) and its extra facts. `format_report` prints a table per intent and the failures;
`summary()` is the JSON line `{"total", "passed", "score", "rules_claims", "by_intent", "failures"}`.
The rules' claims are the turns the rules answered as understood (alone or in front of a model),
a reading they only propose ("Shall I...?", acting on nothing until confirmed) not among them:
their precision (how many of them were right) says whether the rules hand over what they do not
understand, which a hybrid model depends on. All cases run on one event loop, so a backend keeps one
HTTP client for the whole set; it is closed at the end.
"""

from __future__ import annotations

import asyncio
import json
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

from dialogue.engine import DialogueEngine, EngineConfig, TurnResult
from dialogue.errors import DialogueError
from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.intents import RAW_USER_INPUT, SAY
from dialogue.llm.base import ChatModel
from dialogue.llm.rules import RULES
from dialogue.llm.spec import parse_spec
from kb import KB, KbError

T = TypeVar("T")
DEFAULT_SPEAKER = "user1"
_CASE_KEYS = {"id", "scene", "facts", "speaker", "history", "input", "expect"}
#: `then` (an extension of the shared format): the intents that must follow the first, in order,
#: each {"intent": ..., "roles": {...}}; with it, no other intent may be returned.
_EXPECT_KEYS = {"intent", "roles", "clarify", "reply_mentions", "then"}


class EvalError(DialogueError, ValueError):
    """A cases file or scene that is not in the expected format; the message names file and line."""


@dataclass(frozen=True)
class Case:
    id: str
    input: str
    expect: dict[str, Any]
    scene: str | None = None
    facts: tuple[str, ...] = ()
    speaker: str = DEFAULT_SPEAKER
    history: tuple[Utterance, ...] = ()

    @property
    def intent_key(self) -> str:
        return self.expect.get("intent") or "none"


@dataclass
class CaseResult:
    case: Case
    passed: bool
    problems: list[str]
    result: TurnResult


@dataclass
class Report:
    results: list[CaseResult] = field(default_factory=list)

    @property
    def total(self) -> int:
        return len(self.results)

    @property
    def passed(self) -> int:
        return sum(r.passed for r in self.results)

    @property
    def score(self) -> float:
        return self.passed / self.total if self.total else 0.0

    @property
    def claims(self) -> list[CaseResult]:
        """The turns the rules answered as understood (rules mode, or in front of a model), but for
        the readings they only proposed (in front of a model, those are the model's)."""
        return [r for r in self.results
                if r.result.backend == RULES and r.result.understood and not r.result.confirm]  # fmt: skip

    @property
    def claim_precision(self) -> float | None:
        """Of the rules' claims, the share that were right; None when they claimed nothing."""
        claims = self.claims
        return sum(r.passed for r in claims) / len(claims) if claims else None

    def claims_summary(self) -> dict[str, Any]:
        claims, precision = self.claims, self.claim_precision
        return {"claimed": len(claims), "right": sum(r.passed for r in claims),
                "precision": None if precision is None else round(precision, 4)}

    def by_intent(self) -> dict[str, dict[str, float]]:
        out: dict[str, dict[str, float]] = {}
        for r in self.results:
            row = out.setdefault(r.case.intent_key, {"total": 0, "passed": 0, "score": 0.0})
            row["total"] += 1
            row["passed"] += int(r.passed)
        for row in out.values():
            row["score"] = row["passed"] / row["total"]
        return dict(sorted(out.items()))

    def summary(self) -> dict[str, Any]:
        return {
            "total": self.total,
            "passed": self.passed,
            "score": round(self.score, 4),
            "rules_claims": self.claims_summary(),
            "by_intent": self.by_intent(),
            "failures": [r.case.id for r in self.results if not r.passed],
        }


def load_cases(path: Path) -> list[Case]:
    cases = []
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except OSError as exc:
        raise EvalError(f"cannot read {path}: {exc.strerror}") from None
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        where = f"{path}:{number}"
        try:
            raw = json.loads(line)
        except json.JSONDecodeError as exc:
            raise EvalError(f"{where}: not JSON ({exc.msg})") from None
        cases.append(_case(raw, where))
    ids = [c.id for c in cases]
    duplicates = sorted({i for i in ids if ids.count(i) > 1})
    if duplicates:
        raise EvalError(f"{path}: duplicate case ids {duplicates}")
    return cases


def _case(raw: Any, where: str) -> Case:
    if not isinstance(raw, dict):
        raise EvalError(f"{where}: a case must be a JSON object")
    unknown = set(raw) - _CASE_KEYS
    if unknown:
        raise EvalError(f"{where}: unknown keys {sorted(unknown)}")
    for key in ("id", "input"):
        if not isinstance(raw.get(key), str) or not raw[key]:
            raise EvalError(f"{where}: {key!r} must be a non-empty string")
    expect = raw.get("expect")
    if not isinstance(expect, dict) or "intent" not in expect or set(expect) - _EXPECT_KEYS:
        raise EvalError(f"{where}: 'expect' must be an object with 'intent' and only {sorted(_EXPECT_KEYS)}")
    then = expect.get("then", [])
    if not isinstance(then, list) or not all(
        isinstance(t, dict) and isinstance(t.get("intent"), str) and set(t) <= {"intent", "roles"}
        and isinstance(t.get("roles", {}), dict)
        for t in then
    ) or (then and expect["intent"] is None):
        shape = "{'intent': str, 'roles': {...}}"
        raise EvalError(f"{where}: 'expect.then' must be a list of {shape} after an intent")
    speaker = raw.get("speaker", DEFAULT_SPEAKER)
    history = []
    for turn in raw.get("history", []):
        if (
            not isinstance(turn, dict)
            or turn.get("speaker") not in {"user", "robot"}
            or not isinstance(turn.get("text"), str)
        ):
            raise EvalError(f"{where}: history turns are {{'speaker': 'user'|'robot', 'text': str}}")
        history.append(Utterance(speaker if turn["speaker"] == "user" else ASSISTANT_USER_ID, turn["text"]))
    facts = raw.get("facts", [])
    if not isinstance(facts, list) or not all(isinstance(f, str) for f in facts):
        raise EvalError(f"{where}: 'facts' must be a list of statements")
    return Case(raw["id"], raw["input"], expect, raw.get("scene"), tuple(facts), speaker, tuple(history))


def scene_statements(scenes_dir: Path, name: str) -> list[str]:
    path = scenes_dir / f"{name}.txt"
    try:
        text = path.read_text(encoding="utf-8")
    except OSError:
        raise EvalError(f"scene {name!r} not found: {path}") from None
    return [s.strip() for s in text.splitlines() if s.strip() and not s.strip().startswith("#")]


def check(case: Case, result: TurnResult) -> list[str]:
    """What the result gets wrong with respect to the case's expectations (empty: the case passes)."""
    problems = []
    expect = case.expect
    real = [i for i in result.intents if i.intent != RAW_USER_INPUT]
    wanted = expect.get("intent")
    if wanted is None and real:
        problems.append(f"expected no intent, got {real[0].intent}")
    if wanted is not None:
        steps = [{"intent": wanted, "roles": expect.get("roles") or {}}, *expect.get("then", [])]
        if "then" not in expect:
            real = real[:1]  # only the first intent is checked; others may follow it
        if [i.intent for i in real] != [s["intent"] for s in steps]:
            problems.append(f"expected {_names(steps)}, got {_names(real) or 'no intent'}")
        else:
            for n, (step, intent) in enumerate(zip(steps, real, strict=True)):
                where = f"intent {n + 1} " if len(steps) > 1 else ""
                for role, value in (step.get("roles") or {}).items():
                    got = intent.data.get(role)
                    loose = step["intent"] == SAY and role == "object"
                    ok = isinstance(got, str) and (value.lower() in got.lower() if loose else got == value)
                    if not ok:
                        problems.append(f"{where}role {role}: expected {value!r}, got {got!r}")
    if expect.get("clarify") and ("?" not in result.response or real):
        problems.append("expected a clarifying question and no intent")
    for text in expect.get("reply_mentions") or []:
        if text.lower() not in result.response.lower():
            problems.append(f"reply does not mention {text!r}")
    return problems


def _names(steps: Sequence[Any]) -> str:
    return ", ".join(s["intent"] if isinstance(s, dict) else s.intent for s in steps)


def case_kb(case: Case, scenes_dir: Path, kb_factory: Callable[[], KB]) -> KB:
    """A KB with the case's scene and facts (closed again if they do not load)."""
    statements = scene_statements(scenes_dir, case.scene) if case.scene else []
    kb = kb_factory()
    try:
        if statements:
            kb.update(statements)
        if case.facts:
            kb.update(list(case.facts))
    except KbError as exc:
        kb.close()
        raise EvalError(f"case {case.id!r}: bad scene or facts: {exc}") from None
    return kb


def run(
    path: str | Path,
    llm_spec: str = "rules",
    *,
    deadline: float = 5.0,
    kb_factory: Callable[[], KB] = KB,
    model: ChatModel | None = None,
) -> Report:
    """Score the cases of `path` with the backend `llm_spec` names (closed at the end), or with
    `model` (left open: its owner closes it)."""
    cases_path = Path(path)
    cases = load_cases(cases_path)
    scenes = cases_path.parent / "scenes"
    if model is not None:
        return asyncio.run(_run(cases, scenes, model, deadline, kb_factory))
    built = parse_spec(llm_spec).model
    return asyncio.run(closing(_run(cases, scenes, built, deadline, kb_factory), built))


async def closing(work: Awaitable[T], model: ChatModel) -> T:
    """`work`'s result, `model` closed after it (on the same loop: its HTTP client lives there)."""
    try:
        return await work
    finally:
        await model.aclose()


async def _run(
    cases: list[Case], scenes_dir: Path, model: ChatModel, deadline: float, kb_factory: Callable[[], KB]
) -> Report:
    config = EngineConfig(deadline=deadline)
    report = Report()
    for case in cases:
        kb = await asyncio.to_thread(case_kb, case, scenes_dir, kb_factory)
        try:
            engine = DialogueEngine(kb, model, config)
            result = await engine.turn(case.input, speaker=case.speaker, history=case.history)
        finally:
            await asyncio.to_thread(kb.close)
        problems = check(case, result)
        report.results.append(CaseResult(case, not problems, problems, result))
    return report


def claims_text(report: Report) -> str:
    """The rules' claims in words: 'rules' claims: 47/48 right (precision 0.98)'."""
    summary = report.claims_summary()
    if not summary["claimed"]:
        return "rules' claims: none"
    right, claimed, precision = summary["right"], summary["claimed"], summary["precision"]
    return f"rules' claims: {right}/{claimed} right (precision {precision:.2f})"


def format_report(report: Report) -> str:
    lines = [f"{'intent':32} {'passed':>7} {'total':>6} {'score':>6}"]
    for intent, row in report.by_intent().items():
        lines.append(f"{intent:32} {int(row['passed']):7d} {int(row['total']):6d} {row['score']:6.2f}")
    overall = f"{'all':32} {report.passed:7d} {report.total:6d} {report.score:6.2f}"
    lines.append(f"{overall}   {claims_text(report)}")
    failures = [r for r in report.results if not r.passed]
    if failures:
        lines.append("")
        lines.append("failures:")
        for r in failures:
            error = f" [error: {r.result.error_msg}]" if r.result.error_msg else ""
            reply = f"(reply: {r.result.response!r})"
            lines.append(f"- {r.case.id}: {r.case.input!r} -> {'; '.join(r.problems)} {reply}{error}")
    return "\n".join(lines)
