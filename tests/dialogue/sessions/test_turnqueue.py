"""The turns of one dialogue one at a time, in arrival order, none waiting past its own deadline."""

from __future__ import annotations

import asyncio

import pytest

from dialogue.sessions.turnqueue import TurnQueue


def test_late_work_keeps_its_place_and_other_dialogues_do_not_wait() -> None:
    async def run() -> list[str]:
        queue, order = TurnQueue(), []
        first = await queue.take("d1", timeout=1.0)
        late = await queue.take("d1", timeout=0.0)  # the first holds the dialogue: not reached

        async def record() -> None:
            order.append("late")

        queue.later(late, record)
        third = asyncio.ensure_future(queue.take("d1", timeout=5.0))  # arrives after the late one
        other = await queue.take("d2", timeout=1.0)  # another dialogue: free at once
        assert first.reached and not late.reached and other.reached
        order.append("first")
        first.release()
        place = await third
        assert place.reached
        order.append("third")
        place.release()
        await queue.idle()
        return order

    assert asyncio.run(run()) == ["first", "late", "third"]


def test_a_turn_cancelled_while_it_waits_leaves_the_queue_working() -> None:
    async def run() -> bool:
        queue = TurnQueue()
        first = await queue.take("d1", timeout=1.0)
        waiting = asyncio.ensure_future(queue.take("d1", timeout=5.0))
        await asyncio.sleep(0)
        waiting.cancel()
        with pytest.raises(asyncio.CancelledError):
            await waiting
        first.release()
        after = await queue.take("d1", timeout=1.0)
        after.release()
        return after.reached

    assert asyncio.run(run())


def test_failing_late_work_frees_the_place() -> None:
    async def run() -> bool:
        queue = TurnQueue()
        first = await queue.take("d1", timeout=1.0)
        late = await queue.take("d1", timeout=0.0)

        async def fail() -> None:
            raise RuntimeError("the store went away")

        queue.later(late, fail)
        first.release()
        await queue.idle()
        after = await queue.take("d1", timeout=1.0)
        after.release()
        return after.reached

    assert asyncio.run(run())


def test_an_idle_dialogues_place_is_reached_without_waiting_for_the_event_loop() -> None:
    async def run() -> None:
        queue = TurnQueue()
        taking = queue.take("d1", timeout=0.0)
        with pytest.raises(StopIteration) as taken:  # done at its first step: it never yielded
            taking.send(None)
        place = taken.value.value
        assert place.reached
        waiting = asyncio.ensure_future(queue.take("d1", timeout=5.0))  # the dialogue is held now
        await asyncio.sleep(0)
        assert not waiting.done()
        place.release()
        second = await waiting
        assert second.reached
        second.release()
        again = await queue.take("d1", timeout=0.0)  # released and idle again: reached at once
        assert again.reached
        again.release()

    asyncio.run(run())
