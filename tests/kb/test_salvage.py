"""What still reads of a damaged snapshot (issue 26, rerun of attack 7): 512 zero bytes a third
of the way into a snapshot of 88 statements left the 29 before them; the 59 after still read."""

from __future__ import annotations

import pytest

from kb.records import frame
from kb.salvage import salvage

ORO = "http://kb.openrobots.org#"


def statement(i: int) -> str:
    return f"<{ORO}thing_{i}> <{ORO}isOn> <{ORO}table_{i}>"


def snapshot(count: int, bob: int = 0) -> bytes:
    models = {"default": {"add": [statement(i) for i in range(count)], "remove": []}}
    if bob:
        models["bob"] = {"add": [statement(1000 + i) for i in range(bob)], "remove": []}
    return frame({"revision": 88, "models": models,
                  "expiries": [["default", statement(0), 1_000_000.5], ["default", statement(1), 2e6]]})


def test_statements_after_zeroed_bytes_are_kept() -> None:
    data = bytearray(snapshot(88))
    third = len(data) // 3
    data[third:third + 512] = bytes(512)
    found = salvage(bytes(data))
    assert found is not None and found.damaged
    kept = found.state["models"]["default"]["add"]
    # the statements the zeros touched are gone (about 512 / 100 bytes of them), every other stays
    assert all(f'"{s}"'.encode() in data for s in kept)
    assert len(kept) == sum(f'"{statement(i)}"'.encode() in data for i in range(88)) >= 88 - 7
    assert found.after_damage == len([s for s in kept if data.find(f'"{s}"'.encode()) > third])
    assert found.after_damage > 50  # before: 0, the repair kept only the 29 before the damage
    assert found.state["revision"] == 88
    assert found.state["expiries"] == [["default", statement(0), 1_000_000.5], ["default", statement(1), 2e6]]


def test_damage_in_one_model_leaves_the_next_models_in_place() -> None:
    data = bytearray(snapshot(20, bob=10))
    at = data.index(statement(10).encode())
    data[at:at + 30] = b"\xff" * 30
    found = salvage(bytes(data))
    assert found is not None
    assert found.state["models"]["bob"]["add"] == [statement(1000 + i) for i in range(10)]
    assert found.state["models"]["default"]["add"] == [statement(i) for i in range(20) if i != 10]


@pytest.mark.parametrize("cut", [100, 5000])
def test_a_snapshot_cut_short_keeps_what_comes_before_the_cut(cut: int) -> None:
    data = snapshot(88)[:-cut]
    found = salvage(data)
    assert found is not None
    kept = found.state["models"]["default"]["add"]
    assert kept == [statement(i) for i in range(len(kept))]
    assert len(kept) == sum(f'"{statement(i)}"'.encode() in data for i in range(88))


def test_nothing_that_reads_as_a_snapshot_is_none() -> None:
    assert salvage(b"") is None and salvage(bytes(600)) is None
