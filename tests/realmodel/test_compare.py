"""`situated eval --compare` with the real model on a few dev cases: both sides scored, engine grounded."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from dialogue.evaluation.compare import compare, format_comparison
from dialogue.llm.llamacpp import LlamaCppModel
from dialogue.llm.spec import Backend
from tests.dialogue.conftest import EVAL_DIR
from tests.realmodel.conftest import REALMODEL

pytestmark = REALMODEL
CASES = ("kitchen-greet-hello", "kitchen-grab-class", "kitchen-where-support")


def test_compare_runs_both_approaches_with_one_model(local_model: LlamaCppModel, tmp_path: Path) -> None:
    lines = [line for line in (EVAL_DIR / "dev.jsonl").read_text().splitlines() if json.loads(line)["id"] in CASES]
    assert len(lines) == len(CASES)
    (tmp_path / "cases.jsonl").write_text("\n".join(lines) + "\n")
    shutil.copytree(EVAL_DIR / "scenes", tmp_path / "scenes")
    backend = Backend(local_model, "llamacpp:smollm2")
    comparison = compare(tmp_path / "cases.jsonl", "llamacpp:smollm2", deadline=20.0, backend=backend)
    summary = comparison.summary()
    assert summary["tutorial"]["total"] == summary["situated"]["total"] == len(CASES)
    assert summary["situated"]["ungrounded"] == 0  # the engine never emits an unknown referent
    assert all(r.result.response for r in comparison.situated.report.results)
    table = format_comparison(comparison)
    assert "ungrounded referents" in table and "llamacpp:smollm2" in table
