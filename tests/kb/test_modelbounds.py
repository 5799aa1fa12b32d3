"""What models may cost: how many the KB holds, how many statements of its own each other model
holds; past either a write is refused whole, saying which bound and where it is set."""

from __future__ import annotations

from pathlib import Path

import pytest

from kb import KB, KbError
from kb.errors import ModelLimit
from kb.journal import Journal


def test_new_models_past_the_bound_are_refused_and_nothing_changes() -> None:
    kb = KB(max_models=3)  # the robot's and two more
    kb.update(["person_a likes dbr:Tea"], models=["person_a"])
    kb.update(["person_b likes dbr:Tea"], models=["person_b", "person_a"])
    revision = kb.revision
    for models in (["person_c"], ["person_a", "person_c"], ["default", "person_c", "person_d"]):
        with pytest.raises(ModelLimit) as refused:
            kb.update(["person_c likes dbr:Tea"], models=models)
        assert "the KB holds 3 models" in str(refused.value) and "the limit is 3" in str(refused.value)
        assert "max_total_models" in str(refused.value)
    with pytest.raises(ModelLimit):
        kb.apply_models({"person_a": {"add": ["person_a likes dbr:Coffee"]}, "person_c": {"add": ["x y z"]}})
    assert kb.models() == ["default", "person_a", "person_b"] and kb.revision == revision
    assert not kb.exist(["person_a likes dbr:Coffee"], models=["person_a"])  # refused whole
    kb.update(["person_a likes dbr:Milk"], models=["person_a", "person_b", "default"])  # the known ones: fine
    kb.clear()  # the others go: room again
    kb.update(["person_c likes dbr:Tea"], models=["person_c"])


def test_a_models_own_statements_are_bounded_the_robots_are_not() -> None:
    kb = KB(max_model_statements=5)
    kb.update([f"thing_{n} isOn table_1" for n in range(5)], models=["person_a"])
    revision = kb.revision
    with pytest.raises(ModelLimit) as refused:
        kb.update(["thing_9 isOn table_1", "thing_0 isOn table_1"], models=["person_a"])  # one new
    assert str(refused.value) == ("model 'person_a' would hold 6 statements of its own; the limit is 5 "
                                  "(the KB's max_model_statements; the service's limits.max_model_statements)")
    with pytest.raises(ModelLimit, match="model 'person_b' would hold 6 statements"):
        kb.update([f"thing_{n} isOn table_2" for n in range(6)], models=["person_b"])  # a new one too
    assert kb.revision == revision and kb.models() == ["default", "person_a"]
    kb.update(["thing_0 isOn table_1", "thing_1 isOn table_1"], models=["person_a"])  # already held: no growth
    kb.apply(add=["thing_9 isOn table_1"], remove=["thing_0 isOn table_1"], models=["person_a"])  # one for one
    kb.remove(["thing_1 isOn table_1"], models=["person_a"])
    kb.update(["thing_8 isOn table_1"], models=["person_a"])
    kb.update([f"thing_{n} isOn table_3" for n in range(50)])  # the robot's model: no bound
    assert kb.exist(["thing_49 isOn table_3"]) and kb.exist(["thing_8 isOn table_1"], models=["person_a"])


def test_bounds_are_positive_integers_and_none_by_default() -> None:
    kb = KB()
    kb.update(["x y z"], models=[f"m{n}" for n in range(16)])
    assert len(kb.models()) == 17
    for bad in ({"max_models": 0}, {"max_model_statements": -1}, {"max_models": True}, {"max_models": 1.5}):
        with pytest.raises(KbError, match="must be a positive integer"):
            KB(**bad)  # type: ignore[arg-type]


def test_a_journal_written_under_wider_bounds_is_recovered_whole(tmp_path: Path) -> None:
    """Recovery replays what was acknowledged, whatever the bounds of the start; new writes meet them."""
    wide = KB()
    Journal(tmp_path).recover(wide)
    wide.update([f"thing_{n} isOn table_1" for n in range(5)], models=["person_a", "person_b", "person_c"])
    wide.close()
    narrow = KB(max_models=2, max_model_statements=3)
    journal = Journal(tmp_path)
    journal.recover(narrow)
    try:
        assert narrow.models() == ["default", "person_a", "person_b", "person_c"]
        assert narrow.exist(["thing_4 isOn table_1"], models=["person_c"])
        with pytest.raises(ModelLimit):
            narrow.update(["thing_9 isOn table_1"], models=["person_d"])
        with pytest.raises(ModelLimit):
            narrow.update(["thing_9 isOn table_1"], models=["person_a"])
        narrow.remove(["thing_4 isOn table_1"], models=["person_a"])  # shrinking is always allowed
    finally:
        journal.close()
        narrow.close()
