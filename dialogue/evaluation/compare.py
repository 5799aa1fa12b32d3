"""What situated's grounding adds: the same model on the same cases, with and without it.

(a) "tutorial": the approach of the ROS4HRI "zero to LLM" tutorial chatbot (dialogue-compat §4.1): its
answer schema (an enum of its 8 intent types, free-text `object`/`recipient`/`input`/`goal`), its
environment lines "- I see a <class> labeled <label>." built from `myself sees ?obj` and `details()`,
its prompt rules (paraphrased), no validation beyond its pydantic model and no resolution: the
intent's `data` is the `user_intent` taken verbatim (null roles dropped, `type` kept, as it dumps it).
(b) "situated": the dialogue engine (enum-constrained schema, resolution, clarification, repair,
optionally the rules-first hybrid).

Both are scored with `evaluation.check`, and every value of a KB-grounded role that is not an entity id
of the situation (or the speaker) counts as an ungrounded referent. With the `rules` spec, (a) passes
the rules' answer through the tutorial's mapping, so the comparison runs offline too. With a
`hybrid:` spec (or `hybrid=True`) only (b) runs the rules first; (a) always asks the model (the
hybrid model's `llm`). Both passes run on one event loop; a model built here is closed at the end.
"""

from __future__ import annotations

import asyncio
import logging
import string
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ValidationError

from dialogue import intents as I
from dialogue.engine import DialogueEngine, EngineConfig, TurnResult
from dialogue.evaluation.cases import Case, CaseResult, Report, case_kb, check, closing, load_cases
from dialogue.llm.base import ChatMessage, ChatModel, ChatRequest, ModelError, TurnContext
from dialogue.llm.spec import Backend, parse_spec, rules_first
from dialogue.prompts import history_message
from dialogue.reference.grounding import Snapshot
from dialogue.schema import REFERENT_FIELDS
from kb import KB

log = logging.getLogger(__name__)

TUTORIAL_INTENTS = (
    I.BRING_OBJECT,
    I.GRAB_OBJECT,
    I.PLACE_OBJECT,
    I.GUIDE,
    I.MOVE_TO,
    I.SAY,
    I.GREET,
    I.START_ACTIVITY,
)
TutorialType = Literal[
    "__intent_bring_object__",
    "__intent_grab_object__",
    "__intent_place_object__",
    "__intent_guide__",
    "__intent_move_to__",
    "__intent_say__",
    "__intent_greet__",
    "__intent_start_activity__",
]

# The tutorial's rules in our own words (dialogue-compat §4.1); `$` placeholders, safe substitution.
TUTORIAL_PROMPT = string.Template(
    """You are $robot_name, a friendly robot. You are talking with the user whose id is $user_id.
Always answer with a JSON object with the fields "verbal_ack" and "user_intent".
- "verbal_ack" must always be there: a brief acknowledgement you say at once, not a long answer.
- If what you have to say is long or elaborate, return it as an intent of type __intent_say__.
- If the user only asks a question and nothing has to be done, answer in "verbal_ack" and set
  "user_intent" to null.
- If the user greets you, return an __intent_greet__ intent whose "recipient" is $user_id.
- If the user wants you to take something, return an __intent_grab_object__ intent whose "object" is
  the id of that object, but only when such an object is in the description of your environment;
  if it is not, tell the user you have not seen one.
- If the user wants you to carry out a task, return an __intent_start_activity__ intent with the name
  of the activity as "object", for instance cleaning_table.
- If you are not sure what the user wants, set "user_intent" to null and ask for confirmation in
  "verbal_ack"."""
)


class TutorialIntent(BaseModel):
    # No defaults, as in the tutorial: every key is required but may be null.
    type: TutorialType
    object: str | None
    recipient: str | None
    input: str | None
    goal: str | None


class TutorialResponse(BaseModel):
    verbal_ack: str | None
    user_intent: TutorialIntent | None


TUTORIAL_SCHEMA: dict[str, Any] = TutorialResponse.model_json_schema()


def environment_lines(kb: KB) -> list[str]:
    """The tutorial's grounding: one line per seen entity, class and label from `details()`."""
    lines = []
    for row in kb.find(["myself sees ?obj"]):
        details = kb.details(row["obj"])
        label = details.get("label", {}).get("default") or row["obj"]
        try:
            cls = details["attributes"][0]["values"][0]["label"]["default"]
        except (KeyError, IndexError, TypeError):
            cls = "thing"  # the tutorial would fail here; keep going so the case is scored
        lines.append(f"- I see a {cls} labeled {label}.")
    return lines


def tutorial_messages(case: Case, environment: Sequence[str], robot_name: str) -> tuple[ChatMessage, ...]:
    system = TUTORIAL_PROMPT.safe_substitute(robot_name=robot_name, user_id=case.speaker)
    return (
        ChatMessage("system", system),
        *(history_message(u) for u in case.history),
        ChatMessage("system", "\n".join(environment)),
        ChatMessage("user", case.input),
    )


def tutorial_result(content: str) -> TurnResult:
    """The tutorial's mapping: response = verbal_ack, one intent whose data is the whole user_intent."""
    try:
        answer = TutorialResponse.model_validate_json(content)
    except ValidationError as exc:
        return TurnResult("", error_msg=f"invalid answer: {exc.errors()[0]['msg']}", backend="tutorial")
    response = answer.verbal_ack or ""
    wish = answer.user_intent
    if wish is None:
        return TurnResult(response, backend="tutorial")
    data = {k: v for k, v in wish.model_dump().items() if v is not None}
    # Source, modality and confidence are left unset by the tutorial, so priority is 0.
    intent = I.Intent(intent=wish.type, data=data, source="", priority=0)
    return TurnResult(response, (intent,), backend="tutorial")


async def tutorial_turn(model: ChatModel, request: ChatRequest, deadline: float) -> TurnResult:
    try:
        async with asyncio.timeout(deadline):
            result = await model.chat(request, deadline)
    except ModelError as exc:
        return TurnResult("", error_msg=f"{model.name}: {exc}", backend="tutorial")
    except TimeoutError:
        return TurnResult("", error_msg=f"no answer within {deadline:g} s", backend="tutorial")
    return tutorial_result(result.content)


def ungrounded(result: TurnResult, snapshot: Snapshot, speaker: str) -> tuple[int, int]:
    """(referents, ungrounded referents) in the result's intents, over KB-grounded roles."""
    total = bad = 0
    for intent in result.intents:
        if intent.intent == I.RAW_USER_INPUT:
            continue
        spec = I.CATALOGUE.get(intent.intent)
        for role in spec.grounded if spec else REFERENT_FIELDS:
            value = intent.data.get(role)
            if not isinstance(value, str):  # absent (a grounded role's value is always text)
                continue
            total += 1
            bad += value not in snapshot.entities and value != speaker
    return total, bad


@dataclass
class Side:
    """One approach's results: the usual report plus grounding counts and time."""

    name: str
    report: Report
    referents: int = 0
    ungrounded: int = 0
    errors: int = 0
    seconds: float = 0.0

    def add(self, case: Case, result: TurnResult, snapshot: Snapshot) -> None:
        problems = check(case, result)
        self.report.results.append(CaseResult(case, not problems, problems, result))
        total, bad = ungrounded(result, snapshot, case.speaker)
        self.referents += total
        self.ungrounded += bad
        self.errors += bool(result.error_msg)

    def summary(self) -> dict[str, Any]:
        return {
            **self.report.summary(),
            "referents": self.referents,
            "ungrounded": self.ungrounded,
            "errors": self.errors,
            "seconds": round(self.seconds, 1),
        }




@dataclass
class Comparison:
    llm: str
    tutorial: Side
    situated: Side

    def summary(self) -> dict[str, Any]:
        return {"llm": self.llm, "tutorial": self.tutorial.summary(), "situated": self.situated.summary()}


def compare(
    path: str | Path,
    llm_spec: str = "rules",
    *,
    deadline: float = 5.0,
    hybrid: bool = False,
    kb_factory: Callable[[], KB] = KB,
    backend: Backend | None = None,
) -> Comparison:
    """Run the cases with the tutorial's approach, then through the engine, with one model instance.

    The two passes run one after the other (not interleaved) so that a local model's prompt-prefix
    cache serves each approach's static prompt. `backend` (a model already built from `llm_spec`)
    lets a caller share a loaded model.
    """
    cases_path = Path(path)
    cases = load_cases(cases_path)
    owned = backend is None
    backend = backend or parse_spec(llm_spec)
    label = backend.spec + (" --hybrid" if hybrid and not backend.spec.startswith("hybrid:") else "")
    if hybrid:
        backend = rules_first(backend)
    comparison = Comparison(label, Side("tutorial", Report()), Side("situated", Report()))
    run = _passes(comparison, cases, cases_path.parent / "scenes", backend.model, deadline, kb_factory)
    asyncio.run(closing(run, backend.model) if owned else run)
    return comparison


async def _passes(
    comparison: Comparison,
    cases: list[Case],
    scenes_dir: Path,
    model: ChatModel,
    deadline: float,
    kb_factory: Callable[[], KB],
) -> None:
    """The tutorial's pass over the cases, then the engine's."""
    prompted = model.llm or model  # the tutorial always asks the model (the rules only when alone)
    try:
        await prompted.preload()  # loading is not what is compared
    except ModelError as exc:  # every turn will say so, and be scored as failed
        log.warning("%s could not be loaded: %s", prompted.name, exc)
    config = EngineConfig(deadline=deadline)
    for side in (comparison.tutorial, comparison.situated):
        for case in cases:
            kb = await asyncio.to_thread(case_kb, case, scenes_dir, kb_factory)
            try:
                engine = DialogueEngine(kb, model, config)
                snapshot, _lexicon = await asyncio.to_thread(engine.ground)
                started = time.perf_counter()
                if side is comparison.tutorial:
                    # the robot's name as the engine's turns have it: the scene's label of `myself`
                    robot_name = snapshot.robot_name(config.robot_name)
                    context = TurnContext(case.input, case.speaker, snapshot, case.history, None, robot_name)
                    environment = await asyncio.to_thread(environment_lines, kb)
                    messages = tutorial_messages(case, environment, robot_name)
                    request = ChatRequest(messages, TUTORIAL_SCHEMA, context)
                    result = await tutorial_turn(prompted, request, deadline)
                else:
                    result = await engine.turn(case.input, speaker=case.speaker, history=case.history)
                side.seconds += time.perf_counter() - started
            finally:
                await asyncio.to_thread(kb.close)
            side.add(case, result, snapshot)


def claims_cell(report: Report) -> str:
    """The rules' claims of one side: right/claimed and their precision ('-' when none)."""
    claims = report.claims_summary()
    if not claims["claimed"]:
        return f"{'-':>15}"
    return f"{claims['right']:>5}/{claims['claimed']:<3} {claims['precision']:5.2f}"


def format_comparison(comparison: Comparison) -> str:
    a, b = comparison.tutorial, comparison.situated
    rows_a, rows_b = a.report.by_intent(), b.report.by_intent()
    lines = [
        f"comparison with {comparison.llm} on {a.report.total} cases",
        f"{'':32} {'tutorial':>15} {'situated':>15}",
    ]

    def cell(row: dict[str, float] | None) -> str:
        if row is None:
            return f"{'-':>15}"
        return f"{int(row['passed']):>5}/{int(row['total']):<3} {row['score']:5.2f}"

    for intent in sorted(set(rows_a) | set(rows_b)):
        lines.append(f"{intent:32} {cell(rows_a.get(intent))} {cell(rows_b.get(intent))}")
    overall = [
        {"passed": side.report.passed, "total": side.report.total, "score": side.report.score}
        for side in (a, b)
    ]
    lines.append(f"{'all':32} {cell(overall[0])} {cell(overall[1])}")
    lines.append(f"{'ungrounded referents':32} {f'{a.ungrounded}/{a.referents}':>15} "
                 f"{f'{b.ungrounded}/{b.referents}':>15}")
    lines.append(f"{'model errors / invalid answers':32} {a.errors:>15} {b.errors:>15}")
    lines.append(f"{'rules claims right':32} {claims_cell(a.report)} {claims_cell(b.report)}")
    lines.append(f"{'seconds':32} {a.seconds:>15.1f} {b.seconds:>15.1f}")
    return "\n".join(lines)
