"""The layering of docs/ARCHITECTURE.md, enforced: each package imports only the layers below it."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
#: What each package may import from the project (besides itself).
ALLOWED = {
    "kb": set(),
    "scene": {"kb", "ontologies"},
    "dialogue": {"kb", "prompts", "ontologies"},
    "api": {"kb", "scene", "dialogue", "ontologies", "prompts", "bench"},
}
PROJECT = {"kb", "scene", "dialogue", "api", "bench", "ontologies", "prompts"}


def imported_packages(path: Path) -> set[str]:
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            found.add(node.module.split(".")[0])
    return found & PROJECT


@pytest.mark.parametrize("package", sorted(ALLOWED))
def test_a_package_imports_only_the_layers_below_it(package: str) -> None:
    wrong = {
        str(path.relative_to(ROOT)): sorted(bad)
        for path in sorted((ROOT / package).rglob("*.py"))
        if (bad := imported_packages(path) - ALLOWED[package] - {package})
    }
    assert wrong == {}


def test_the_evaluation_tool_is_not_imported_by_run_time_code() -> None:
    users = [
        str(path.relative_to(ROOT))
        for package in ("kb", "scene", "dialogue", "api")
        for path in sorted((ROOT / package).rglob("*.py"))
        if "evaluation" not in path.parts and path.name != "cli.py"
        and any(
            isinstance(node, ast.ImportFrom) and (node.module or "").startswith("dialogue.evaluation")
            for node in ast.walk(ast.parse(path.read_text()))
        )
    ]
    assert users == []
