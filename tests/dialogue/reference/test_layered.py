"""`Layered` behaves as an immutable dict, whatever the sequence of versions and folds."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from dialogue.reference import layered
from dialogue.reference.layered import GONE, Gone, Layered

changes = st.dictionaries(st.integers(0, 40), st.one_of(st.integers(), st.just(GONE)), max_size=12)


@given(st.dictionaries(st.integers(0, 40), st.integers(), max_size=30), st.lists(changes, max_size=30))
def test_every_version_equals_its_dict_and_older_versions_never_change(
    base: dict[int, int], steps: list[dict[int, int | Gone]]
) -> None:
    layered.MIN_TOP, saved = 4, layered.MIN_TOP  # small folds, so the tests exercise them
    try:
        versions = [(Layered(dict(base)), dict(base))]
        for step in steps:
            current, model = versions[-1]
            model = {**model, **{k: v for k, v in step.items() if not isinstance(v, Gone)}}
            for key in [k for k, v in step.items() if isinstance(v, Gone)]:
                model.pop(key, None)
            versions.append((current.evolve(step), model))
        for version, model in versions:
            assert dict(version) == model and len(version) == len(model)
            assert all((k in version) == (k in model) for k in range(42))
    finally:
        layered.MIN_TOP = saved
