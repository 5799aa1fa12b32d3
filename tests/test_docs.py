"""Examples in the docs run: the Python examples of the README and the guides (docs/*.md), and every
docstring example (doctest). Shell examples run in tests/test_docs_examples.py."""

from __future__ import annotations

import doctest
import importlib
import pkgutil
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
PACKAGES = ("kb", "scene", "dialogue", "api", "bench")
#: Import rclpy and the generated ROS interfaces, which the test process never has: their behaviour
#: is tested on a real graph (tests/api/ros), the README's ROS example too (```python ros).
NEEDS_ROS = ("api.ros.node.", "api.ros.client.kb")
_PYTHON_BLOCK = re.compile(r"```python\n(.*?)```", re.S)


def _modules() -> list[str]:
    names: list[str] = []
    for package in PACKAGES:
        module = importlib.import_module(package)
        names.append(package)
        names.extend(info.name for info in pkgutil.walk_packages(module.__path__, package + "."))
    return names


PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def test_the_readme_and_the_guides_have_python_examples() -> None:
    assert _PYTHON_BLOCK.findall((ROOT / "README.md").read_text()), "the README has Python examples"
    assert _PYTHON_BLOCK.findall((ROOT / "docs" / "knowledge-base.md").read_text()), "the KB guide has examples"


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_every_python_block_of_the_page_is_an_example_that_runs(page: Path) -> None:
    blocks = _PYTHON_BLOCK.findall(page.read_text())
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    for number, block in enumerate(blocks, 1):
        # A block that is not written as a session would never be checked: refuse it.
        assert block.lstrip().startswith(">>>"), f"{page.name} Python block {number} is not a doctest"
        test = parser.get_doctest(block, {}, f"{page.name} block {number}", str(page), 0)
        runner.run(test)
    assert runner.failures == 0, f"{runner.failures} example(s) of {page.name} failed; see the output above"


@pytest.mark.parametrize("name", [n for n in _modules() if not n.endswith("__main__") and not n.startswith(NEEDS_ROS)])
def test_docstring_examples_run(name: str) -> None:
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS, verbose=False)
    assert result.failed == 0
