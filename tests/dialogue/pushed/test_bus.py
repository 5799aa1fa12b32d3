"""The intent bus: numbers, filters, replay after a sequence number, gaps, slow readers."""

from __future__ import annotations

import asyncio
import threading
import time

import pytest

from dialogue import intents as I
from dialogue.pushed.bus import Gap, IntentBus, Reader, clock_first
from dialogue.pushed.events import IntentFilter, Pushed


def greet(person: str) -> I.Intent:
    return I.make_intent(I.GREET, {"recipient": person}, source=I.ROBOT_ITSELF, confidence=1.0)


def bring(person: str) -> I.Intent:
    return I.make_intent(I.BRING_OBJECT, {"object": "cup_1", "recipient": person}, source=person,
                         confidence=0.9)


async def drain(reader: Reader, n: int) -> list[Pushed]:
    return [event for _ in range(n) if (event := await asyncio.wait_for(reader.next(), 10)) is not None]


def test_events_are_numbered_in_order_with_where_they_came_from() -> None:
    bus = IntentBus()
    first = bus.publish("dialogue", bring("person_a"), "default", "OK, I will bring the cup to you.")
    second = bus.publish("initiative", greet("person_b"), response="Hello!")
    assert (first.seq, second.seq, bus.last_seq) == (1, 2, 2)
    assert first.as_json()["intent"] == bring("person_a").model_dump(mode="json")
    assert second.as_json() | {"time": 0} == {"seq": 2, "time": 0, "origin": "initiative", "dialogue_id": None,
                                               "response": "Hello!", "intent": greet("person_b").model_dump()}


def test_an_event_keeps_when_it_was_emitted_when_told() -> None:
    bus = IntentBus()
    before = time.time()
    assert bus.publish("dialogue", greet("person_a"), "hall", at=12.5).time == 12.5  # another process's turn
    assert bus.publish("dialogue", greet("person_a"), "hall").time >= before  # else now


def test_a_reader_gets_the_buffered_events_after_its_number_then_the_live_ones() -> None:
    async def run() -> list[int]:
        bus = IntentBus()
        for n in range(5):
            bus.publish("dialogue", bring(f"p{n}"), "default")
        reader = bus.subscribe(asyncio.get_running_loop(), after=2)
        assert reader.gap is None
        bus.publish("dialogue", bring("p5"), "default")
        return [e.seq for e in await drain(reader, 4)]

    assert asyncio.run(run()) == [3, 4, 5, 6]


def test_resuming_while_others_publish_loses_nothing_and_repeats_nothing() -> None:
    async def run() -> list[int]:
        bus = IntentBus(buffer=10_000, max_queued=10_000)
        stop = threading.Event()

        def publish() -> None:
            while not stop.is_set() and bus.last_seq < 3000:
                bus.publish("dialogue", bring("p"), "d")

        worker = threading.Thread(target=publish)
        worker.start()
        while bus.last_seq < 100:
            await asyncio.sleep(0.001)
        reader = bus.subscribe(asyncio.get_running_loop(), after=50)
        worker.join()
        stop.set()
        got: list[int] = []
        while len(got) < bus.last_seq - 50:
            event = await asyncio.wait_for(reader.next(), 10)
            assert event is not None
            got.append(event.seq)
        return got

    got = asyncio.run(run())
    assert got == list(range(51, 51 + len(got)))


def test_filters_by_source_intent_origin_and_dialogue() -> None:
    async def run(flt: IntentFilter) -> list[int]:
        bus = IntentBus()
        bus.publish("dialogue", bring("person_a"), "d1")
        bus.publish("initiative", greet("person_a"))
        bus.publish("dialogue", bring("person_b"), "d2")
        events, _ = bus.since(0, flt)
        return [e.seq for e in events]

    assert asyncio.run(run(IntentFilter.of(sources=["person_b"]))) == [3]
    assert asyncio.run(run(IntentFilter.of(intents=[I.GREET]))) == [2]
    assert asyncio.run(run(IntentFilter.of(origins=["dialogue"]))) == [1, 3]
    assert asyncio.run(run(IntentFilter.of(dialogues=["d1", "d2"], sources=["person_a"]))) == [1]
    with pytest.raises(ValueError, match="unknown origin"):
        IntentFilter.of(origins=["radio"])


def test_what_the_buffer_lost_and_a_number_from_before_a_restart_are_gaps() -> None:
    bus = IntentBus(buffer=3)
    for n in range(6):
        bus.publish("dialogue", bring(f"p{n}"), "d")
    events, gap = bus.since(1)
    assert [e.seq for e in events] == [4, 5, 6] and gap == Gap(2, 3)
    assert bus.since(3) == (events, None)
    events, gap = bus.since(40)  # from an earlier run of the service: all of this one's follow
    assert [e.seq for e in events] == [4, 5, 6] and gap == Gap(1, 3, restarted=True)


def say(text: str) -> I.Intent:
    return I.make_intent(I.SAY, {"object": text}, source=I.ROBOT_ITSELF, confidence=1.0)


def test_the_buffer_is_bounded_in_bytes_the_newest_always_kept() -> None:
    bus = IntentBus(buffer=1000, buffer_bytes=10_000)
    sizes = [bus.publish("dialogue", say("x" * 900), "d").size for _ in range(30)]  # about 27 KB
    events, gap = bus.since(0)
    assert sum(e.size for e in events) <= 10_000 < sum(e.size for e in events) + sizes[0]
    assert [e.seq for e in events] == list(range(31 - len(events), 31)) and gap == Gap(1, 30 - len(events))
    huge = bus.publish("dialogue", say("y" * 50_000), "d")  # larger than the bound alone: kept, alone
    assert bus.since(0)[0] == [huge]


def test_a_reader_whose_queue_passes_the_bytes_is_ended_as_too_slow() -> None:
    async def run() -> tuple[str | None, int]:
        bus = IntentBus(max_queued=1000, buffer_bytes=5_000)
        slow = bus.subscribe(asyncio.get_running_loop())
        for _ in range(10):  # about 9 KB, in ten events
            bus.publish("dialogue", say("x" * 900), "d")
        await asyncio.sleep(0)
        got = await drain(slow, 10)
        return slow.end_reason, len(got)

    reason, got = asyncio.run(run())
    assert reason is not None and reason.startswith("overflow") and 1 <= got < 10


def test_a_reader_too_slow_is_ended_and_the_others_are_not_held_up() -> None:
    async def run() -> tuple[str | None, int]:
        bus = IntentBus(max_queued=3)
        slow = bus.subscribe(asyncio.get_running_loop())
        for n in range(5):
            bus.publish("dialogue", bring(f"p{n}"), "d")
        await asyncio.sleep(0)  # the pushes land on the loop
        got = await drain(slow, 4)
        return slow.end_reason, len(got)

    reason, got = asyncio.run(run())
    assert reason is not None and reason.startswith("overflow") and got == 3


def test_readers_are_bounded_and_end_at_shutdown() -> None:
    async def run() -> str | None:
        bus = IntentBus(max_readers=1)
        reader = bus.subscribe(asyncio.get_running_loop())
        with pytest.raises(ValueError, match="the limit is 1"):
            bus.subscribe(asyncio.get_running_loop())
        bus.shutdown()
        assert await asyncio.wait_for(reader.next(), 10) is None
        return reader.end_reason

    assert asyncio.run(run()) == "service stopping"


def test_listeners_get_every_event_in_the_publishers_thread() -> None:
    bus = IntentBus()
    seen: list[int] = []
    bus.on_publish(lambda event: seen.append(event.seq))
    bus.publish("dialogue", bring("p"), "d")
    bus.publish("initiative", greet("p"))
    assert seen == [1, 2]


def test_a_number_of_an_earlier_run_is_a_restart_however_far_the_new_run_has_got() -> None:
    before = IntentBus(first=clock_first())
    for n in range(5):
        before.publish("dialogue", bring(f"p{n}"), "d")
    time.sleep(0.05)  # the service restarts: the clock moves on (by far more than five milliseconds)
    after = IntentBus(first=clock_first())
    for n in range(20):  # more than the earlier run pushed: numbering from 1, 5 would be this run's
        after.publish("dialogue", bring(f"q{n}"), "d")
    events, gap = after.since(before.last_seq)
    assert gap is not None and gap.restarted and [e.seq for e in events] == list(range(after.first, after.first + 20))
    assert after.since(0) == (events, None)  # 0: nothing seen yet, all of this run


def test_numbers_start_from_the_first_given() -> None:
    bus = IntentBus(first=100)
    assert bus.last_seq == 99 and bus.publish("initiative", greet("p")).seq == 100
    assert bus.since(0)[1] is None and bus.since(99)[1] is None and bus.since(50)[1] == Gap(100, 99, restarted=True)
