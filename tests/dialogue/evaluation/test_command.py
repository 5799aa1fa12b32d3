"""`situated eval`'s command: the shipped HuRIC development set is what it runs without a file."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from dialogue.evaluation.cases import load_cases, scene_statements
from dialogue.evaluation.command import default_cases, main

REPO = Path(__file__).parents[3]
HURIC = REPO / "eval" / "huric"


def test_without_a_file_eval_runs_the_huric_set_a_clone_has() -> None:
    assert default_cases() == HURIC / "dev.jsonl"
    cases = load_cases(default_cases())
    assert len(cases) == 133 and all(c.id.startswith("huric-") for c in cases)
    for case in cases:  # every scene a case names is shipped, and reads
        assert case.scene is not None and scene_statements(HURIC / "scenes", case.scene)


def test_the_huric_set_ships_with_its_licence_and_attribution() -> None:
    assert "Apache License" in (HURIC / "LICENSE").read_text()
    for name in ("NOTICE", "README.md"):
        text = " ".join((HURIC / name).read_text().split())
        assert "github.com/crux82/huric" in text and "Bastianelli" in text and "Human Robot Interaction Corpus" in text


def test_eval_of_the_shipped_file_works_from_a_clone(tmp_path: Path) -> None:
    """`situated eval eval/huric/dev.jsonl`, as the docs say it, on the first cases (the full run is
    the evaluation's, not the tests')."""
    subset = tmp_path / "huric" / "dev.jsonl"
    subset.parent.mkdir()
    subset.write_text("".join((HURIC / "dev.jsonl").read_text().splitlines(keepends=True)[:4]))
    (subset.parent / "scenes").symlink_to(HURIC / "scenes")
    done = subprocess.run([sys.executable, "-m", "api.cli", "eval", str(subset), "--json"], cwd=REPO,
                          capture_output=True, text=True, timeout=240, check=False)
    assert done.returncode == 0, done.stderr[-2000:]
    summary = json.loads(done.stdout.splitlines()[-1])
    assert summary["total"] == 4 and summary["by_intent"]["__intent_move_to__"]["total"] == 4
    cold = subprocess.run([sys.executable, "-m", "api.cli", "eval", "-h"], cwd=REPO, capture_output=True,
                          text=True, check=True)
    assert "eval/huric/dev.jsonl" in " ".join(cold.stdout.split())


def test_a_file_and_compare_together_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exited:
        main(["a.jsonl", "--compare", "b.jsonl"])
    assert exited.value.code == 2 and "not both" in capsys.readouterr().err
