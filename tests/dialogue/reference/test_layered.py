"""`Layered` behaves as an immutable dict, whatever the sequence of versions and folds."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
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


@settings(max_examples=200)
@given(st.lists(st.integers(0, 40)), st.lists(st.tuples(st.booleans(), st.integers(0, 40)), max_size=60))
def test_sorted_chunks_stay_sorted_and_versions_stay_as_they_were(start: list[int],
                                                                  steps: list[tuple[bool, int]]) -> None:
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(layered, "CHUNK", 2)  # splits and emptied chunks on small inputs
        version = layered.SortedChunks(set(start))
        model = sorted(set(start))
        history = [(version, list(model))]
        for insert, item in steps:
            if insert and item not in model:
                version = version.insert(item)
                model = sorted([*model, item])
            elif not insert and item in model:
                version = version.remove(item)
                model.remove(item)
            history.append((version, list(model)))
        for old, expected in history:
            assert list(old) == expected and len(old) == len(expected)
            assert list(old.before(20)) == [x for x in expected if x < 20]


def test_buckets_are_dicts_while_small_and_layered_once_large() -> None:
    small = layered.rebucket(None, dict.fromkeys(range(3)))
    assert isinstance(small, dict) and set(small) == {0, 1, 2}
    large = layered.rebucket(small, dict.fromkeys(range(3, layered.SMALL_BUCKET + 5)))
    assert isinstance(large, Layered) and len(large) == layered.SMALL_BUCKET + 5
    smaller = layered.rebucket(large, {0: GONE, 1: GONE})
    assert isinstance(smaller, Layered) and 0 not in smaller and len(smaller) == layered.SMALL_BUCKET + 3
    assert len(large) == layered.SMALL_BUCKET + 5 and 0 in large  # the old version stays
    assert layered.rebucket(small, {0: GONE, 1: GONE, 2: GONE}) is GONE

