"""The cyclic collector: off while a bulk change runs, and kept off what a service keeps."""

from __future__ import annotations

import gc

import pytest

from kb.gcpause import BULK, paused, settle


def test_a_bulk_change_runs_without_the_collector_and_gives_it_back() -> None:
    assert gc.isenabled()
    with paused(BULK):
        assert not gc.isenabled()
    assert gc.isenabled()
    with pytest.raises(RuntimeError), paused(BULK):
        raise RuntimeError("the change failed")
    assert gc.isenabled()  # however it ends


def test_a_small_change_keeps_the_collector_and_a_caller_that_turned_it_off_keeps_it_off() -> None:
    with paused(BULK - 1):
        assert gc.isenabled()
    gc.disable()
    try:
        with paused(BULK):
            pass
        assert not gc.isenabled()
    finally:
        gc.enable()


def test_settled_objects_are_left_to_the_collector_no_more() -> None:
    before = gc.get_freeze_count()
    kept = [{"triple": i} for i in range(1000)]
    settle()
    assert gc.get_freeze_count() >= before + len(kept)
    gc.unfreeze()  # (this process goes on testing: its objects back to the collector)
