"""The layering of docs/ARCHITECTURE.md, enforced: each package imports only the layers below it."""

from __future__ import annotations

import ast
from graphlib import CycleError, TopologicalSorter
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


def _module(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imported_modules(path: Path, modules: set[str]) -> set[str]:
    """The project's modules a file imports (a name imported from a package is its submodule when
    it is one), type-checking imports included: a cycle is one whatever guards it."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            found.update(f"{node.module}.{a.name}" if f"{node.module}.{a.name}" in modules else node.module
                         for a in node.names)  # fmt: skip
    return found & modules


def test_no_module_of_dialogue_imports_one_that_imports_it_back() -> None:
    paths = {_module(path): path for path in sorted((ROOT / "dialogue").rglob("*.py"))}
    graph = {name: imported_modules(path, set(paths)) - {name} for name, path in paths.items()}
    try:
        list(TopologicalSorter(graph).static_order())
    except CycleError as cycle:
        pytest.fail(f"an import cycle: {' -> '.join(cycle.args[1])}")


#: dialogue/ keeps at most this many modules at its top level; the rest are folders, one per concept.
TOP_LEVEL_MODULES = 16


def test_dialogue_keeps_few_modules_at_its_top_level() -> None:
    assert len(list((ROOT / "dialogue").glob("*.py"))) <= TOP_LEVEL_MODULES
