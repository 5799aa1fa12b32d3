"""The thread -> asyncio bridge of KB events, without HTTP."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from api.errors import ApiError
from api.subscriptions import EventHub
from kb import KB
from kb.errors import TooManyRows


@pytest.fixture(scope="module")
def kb() -> KB:
    return KB()


def test_rows_cross_threads_and_the_last_listener_unsubscribes(kb: KB) -> None:
    async def scenario() -> None:
        loop = asyncio.get_running_loop()
        hub = EventHub(kb, max_listeners=2)
        one = hub.open(["?x isOn shelf_9"], False, None, loop)
        two = hub.open(["?x isOn shelf_9"], False, None, loop)
        assert one.sub_id == two.sub_id
        with pytest.raises(ApiError) as refused:
            hub.open(["?x isIn room_9"], False, None, loop)
        assert refused.value.status == 429
        await asyncio.to_thread(kb.update, ["box_1 isOn shelf_9"])  # delivered from another thread
        assert await asyncio.wait_for(one.next_rows(), 30) == [{"x": "box_1"}]
        assert await asyncio.wait_for(two.next_rows(), 30) == [{"x": "box_1"}]
        hub.close(one)
        assert hub.listener_count == 1
        hub.close(two)
        assert hub.listener_count == 0
        assert kb.unsubscribe(one.sub_id) is False  # the hub removed it

    asyncio.run(scenario())


def test_one_shot_ends_and_a_new_subscription_starts_fresh(kb: KB) -> None:
    async def scenario() -> None:
        loop = asyncio.get_running_loop()
        hub = EventHub(kb, max_listeners=4)
        first = hub.open(["?x isOn shelf_8"], True, None, loop)
        await asyncio.to_thread(kb.update, ["box_2 isOn shelf_8"])
        assert await asyncio.wait_for(first.next_rows(), 30) == [{"x": "box_2"}]
        assert await asyncio.wait_for(first.next_rows(), 30) is None
        assert first.end_reason == "one_shot"
        second = hub.open(["?x isOn shelf_8"], True, None, loop)
        await asyncio.to_thread(kb.update, ["box_3 isOn shelf_8"])
        assert await asyncio.wait_for(second.next_rows(), 30) == [{"x": "box_3"}]
        hub.close(first)
        hub.close(second)
        assert hub.listener_count == 0

    asyncio.run(scenario())


def test_a_slow_reader_is_ended_not_buffered_forever(kb: KB) -> None:
    async def scenario() -> None:
        loop = asyncio.get_running_loop()
        hub = EventHub(kb, max_listeners=1, max_queued=2)
        slow = hub.open(["?x isOn shelf_7"], False, None, loop)
        for i in range(4):
            await asyncio.to_thread(kb.update, [f"box_{i} isOn shelf_7"])
        await asyncio.sleep(0.05)
        rows = [await asyncio.wait_for(slow.next_rows(), 30) for _ in range(3)]
        assert rows[:2] == [[{"x": "box_0"}], [{"x": "box_1"}]] and rows[2] is None
        assert slow.end_reason is not None and slow.end_reason.startswith("overflow")
        hub.shutdown()
        assert hub.listener_count == 0

    asyncio.run(scenario())


class _EndingAtOnce(KB):
    """A KB whose commit ends each new subscription between its subscribe and its first listener
    (the window a real commit can fall into)."""

    def subscribe(self, *args: Any, **kwargs: Any) -> str:
        sub_id = super().subscribe(*args, **kwargs)
        kwargs["on_error"](TooManyRows(3))
        return sub_id


def test_a_subscription_ended_while_it_opens_still_tells_its_listener() -> None:
    async def scenario() -> None:
        hub = EventHub(_EndingAtOnce(), max_listeners=2, query_timeout=5.0, max_rows=3)
        listener = hub.open(["?x isOn shelf_7"], False, None, asyncio.get_running_loop())
        assert await asyncio.wait_for(listener.next_rows(), 30) is None
        assert listener.error is not None and listener.error["code"] == "too_many_rows"
        hub.close(listener)
        assert hub.listener_count == 0

    asyncio.run(scenario())


class RecordingSink:
    """A sink other than a stream's listener (as the ROS node's event topics are)."""

    def __init__(self, sub_id: str) -> None:
        self.sub_id = sub_id
        self.got: list[tuple[list[Any], bool]] = []
        self.errors: list[dict[str, Any]] = []

    def push(self, rows: list[Any], last: bool = False) -> None:
        self.got.append((rows, last))

    def fail(self, error: dict[str, Any]) -> None:
        self.errors.append(error)

    def end(self, reason: str) -> None:
        self.errors.append({"reason": reason})


def test_any_sink_shares_the_subscriptions_and_the_limit_of_stream_listeners(kb: KB) -> None:
    async def scenario() -> None:
        loop = asyncio.get_running_loop()
        hub = EventHub(kb, max_listeners=2)
        stream = hub.open(["?x isOn shelf_7"], True, None, loop)
        sink = hub.attach(["?x isOn shelf_7"], True, None, RecordingSink)
        assert sink.sub_id == stream.sub_id
        with pytest.raises(ApiError) as refused:
            hub.attach(["?x isIn room_7"], False, None, RecordingSink)
        assert refused.value.status == 429
        await asyncio.to_thread(kb.update, ["box_7 isOn shelf_7"])
        assert await asyncio.wait_for(stream.next_rows(), 30) == [{"x": "box_7"}]
        assert sink.got == [([{"x": "box_7"}], True)]  # one-shot: the last rows
        hub.close(sink)
        hub.close(stream)
        assert hub.listener_count == 0

    asyncio.run(scenario())
