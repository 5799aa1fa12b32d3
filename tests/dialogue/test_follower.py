"""A worker thread fed by a KB's commits: items picked under the lock, handled in order on the worker."""

from __future__ import annotations

import threading
from typing import Any

from dialogue.follower import CommitFollower
from kb import KB, KbError


def added(commit: Any) -> list[str]:
    return [str(s) for delta in commit.deltas for s, _, _ in delta.asserted_added]


def test_items_are_handled_in_commit_order_on_the_worker_and_a_kb_error_skips_one() -> None:
    kb = KB()
    handled: list[tuple[str, str]] = []

    def handle(item: str) -> None:
        if item.endswith("bad"):
            raise KbError("refused")
        handled.append((item.rsplit("#", 1)[-1], threading.current_thread().name))

    follower = CommitFollower(kb, "test-follower", added, handle, max_pending=10)
    assert follower.start()
    try:
        kb.update(["a_1 isIn k"])
        kb.update(["a_bad isIn k"])
        kb.update(["a_2 isIn k"])
        follower.join()
        assert handled == [("a_1", "test-follower"), ("a_2", "test-follower")]
    finally:
        follower.stop()
        kb.close()


def test_a_kb_without_commits_is_not_followed() -> None:
    class Replica:
        pass

    follower = CommitFollower(Replica(), "x", added, print, max_pending=1)  # type: ignore[arg-type]
    assert not follower.start()
    follower.stop()
