"""Event topics without ROS: a real KB and event hub, topics whose subscribers the test sets, a
clock it moves. What is published, held, dropped, and when a topic ends."""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from api.errors import ApiError
from api.ros.eventtopics import EventTopic, EventTopics, Hold, Sweeper
from api.subscriptions import EventHub
from kb import KB, KbError

HOLD = Hold(count=3, seconds=10.0, grace=1.0)


class FakeTopic:
    def __init__(self, sub_id: str) -> None:
        self.name = f"/kb/events/{sub_id}"
        self.count = 0
        self.sent: list[Any] = []
        self.closed = False

    def subscribers(self) -> int:
        return self.count

    def publish(self, data: str) -> None:
        assert not self.closed
        self.sent.append(json.loads(data))

    def close(self) -> None:
        self.closed = True


class Clock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


class Graph:
    """A KB, its hub, the topics made, and the clock."""

    def __init__(self, max_listeners: int = 8, max_rows: int | None = None) -> None:
        self.kb = KB()
        self.hub = EventHub(self.kb, max_listeners=max_listeners, max_rows=max_rows)
        self.clock = Clock()
        self.made: dict[str, list[FakeTopic]] = {}
        self.topics = EventTopics(self.hub, self._make, HOLD, self.clock)

    def _make(self, sub_id: str) -> FakeTopic:
        topic = FakeTopic(sub_id)
        self.made.setdefault(sub_id, []).append(topic)
        return topic

    def subscribe(self, *patterns: str, one_shot: bool = False, models: list[str] | None = None) -> FakeTopic:
        made = self.topics.subscribe(list(patterns), one_shot, models)
        topic = made.topic
        assert isinstance(topic, FakeTopic)
        return topic


@pytest.fixture
def graph() -> Iterator[Graph]:
    g = Graph()
    yield g
    g.topics.close()
    g.kb.close()


def test_triggers_are_published_as_knowledge_core_does(graph: Graph) -> None:
    graph.kb.add("joe rdf:type Robot")  # true before: the baseline, no trigger
    made = graph.topics.subscribe(["?robot rdf:type Robot"], False, None)
    topic = made.topic
    assert isinstance(topic, FakeTopic) and topic.name == f"/kb/events/{made.sub_id}"
    topic.count = 1
    graph.kb.add(["ari rdf:type Robot", "bill rdf:type Human"])
    graph.kb.add("ari rdf:type Robot")  # nothing new
    graph.kb.add("tiago rdf:type Robot")
    graph.kb.remove("ari rdf:type Robot")
    graph.kb.add("ari rdf:type Robot")  # gone and back: new again
    assert topic.sent == [[{"robot": "ari"}], [{"robot": "tiago"}], [{"robot": "ari"}]]


def test_identical_requests_share_one_id_and_topic(graph: Graph) -> None:
    graph.kb.add("alice_mind knows cup", ["alice"])
    first = graph.topics.subscribe(["?a sees ?b"], False, None)
    assert graph.topics.subscribe(["?a sees ?b"], False, []) is first
    assert graph.topics.subscribe(["?a sees ?b"], True, None) is not first
    assert graph.topics.subscribe(["?a sees ?b"], False, ["alice"]) is not first
    assert first.sub_id.startswith("evt_") and len(graph.topics) == 3
    assert graph.hub.listener_count == 3


def test_triggers_before_the_first_subscriber_are_held_then_published_in_order(graph: Graph) -> None:
    topic = graph.subscribe("?x isIn kitchen")
    graph.kb.add("cup_1 isIn kitchen")  # nobody has subscribed yet
    graph.kb.add("cup_2 isIn kitchen")
    assert topic.sent == [] and graph.topics.tick() == []
    topic.count = 1  # the client's subscription is discovered
    assert graph.topics.tick() == []
    assert topic.sent == [[{"x": "cup_1"}], [{"x": "cup_2"}]]
    graph.kb.add("cup_3 isIn kitchen")
    assert topic.sent[-1] == [{"x": "cup_3"}]


def test_at_most_hold_count_triggers_are_held_the_oldest_dropped(graph: Graph) -> None:
    topic = graph.subscribe("?x isIn kitchen")
    for n in range(5):
        graph.kb.add(f"cup_{n} isIn kitchen")
    topic.count = 1
    graph.topics.tick()
    assert topic.sent == [[{"x": f"cup_{n}"}] for n in (2, 3, 4)]


def test_a_topic_nobody_subscribes_to_in_time_ends_and_frees_its_subscription(graph: Graph) -> None:
    topic = graph.subscribe("?x isIn kitchen")
    graph.kb.add("cup_1 isIn kitchen")
    graph.clock.now += 9.0
    graph.subscribe("?x isIn kitchen")  # requested again: the wait starts again
    graph.clock.now += 9.0
    assert graph.topics.tick() == []
    graph.clock.now += 1.5
    [(ended, reason)] = graph.topics.tick()
    assert "nobody subscribed to /kb/events/" in reason and "1 trigger(s) not delivered" in reason
    assert topic.closed and topic.sent == [] and len(graph.topics) == 0
    assert graph.hub.listener_count == 0 and graph.kb.unsubscribe(ended.sub_id) is False


def test_a_topic_that_had_a_subscriber_and_has_none_ends_as_in_knowledge_core(graph: Graph) -> None:
    topic = graph.subscribe("?x isIn kitchen")
    topic.count = 1
    graph.kb.add("cup_1 isIn kitchen")
    topic.count = 0  # the client went
    graph.kb.add("cup_2 isIn kitchen")  # not published: nobody listens
    topic.count = 1  # a subscriber comes back: the event is gone all the same
    graph.kb.add("cup_3 isIn kitchen")
    assert topic.sent == [[{"x": "cup_1"}]]
    [(_, reason)] = graph.topics.tick()
    assert reason == f"nobody listens to {topic.name} any more" and topic.closed
    renewed = graph.subscribe("?x isIn kitchen")  # a new request: a new subscription, a new baseline
    assert renewed is not topic and renewed.name == topic.name


def test_the_sweep_ends_an_abandoned_topic_without_waiting_for_a_trigger(graph: Graph) -> None:
    topic = graph.subscribe("?x isIn kitchen")
    topic.count = 1
    assert graph.topics.tick() == []
    topic.count = 0
    [(_, reason)] = graph.topics.tick()
    assert "nobody listens" in reason and graph.hub.listener_count == 0


def test_a_one_shot_topic_publishes_once_and_ends_after_its_grace(graph: Graph) -> None:
    topic = graph.subscribe("?h rdf:type Human", one_shot=True)
    topic.count = 1
    graph.kb.add("joe rdf:type Human")
    graph.kb.add("john rdf:type Human")
    assert topic.sent == [[{"h": "joe"}]]
    assert graph.topics.tick() == [] and not topic.closed
    assert graph.hub.listener_count == 0  # its subscription is over: its place is free
    again = graph.subscribe("?h rdf:type Human", one_shot=True)  # the same id, a new subscription
    assert again is not topic
    graph.clock.now += 1.5
    ended = graph.topics.tick()
    assert [t.topic for t, _ in ended] == [topic] and "one-shot" in ended[0][1]
    assert not again.closed


def test_a_one_shot_trigger_held_before_the_first_subscriber_is_still_delivered(graph: Graph) -> None:
    topic = graph.subscribe("?h rdf:type Human", one_shot=True)
    graph.kb.add("joe rdf:type Human")
    graph.clock.now += 5.0
    assert graph.topics.tick() == []
    topic.count = 1
    graph.topics.tick()
    assert topic.sent == [[{"h": "joe"}]] and not topic.closed
    graph.clock.now += 1.5
    assert len(graph.topics.tick()) == 1 and topic.closed


def test_a_subscription_ended_past_the_query_limits_ends_its_topic() -> None:
    g = Graph(max_rows=2)
    topic = g.subscribe("?x isIn ?room")
    topic.count = 1
    g.kb.add(["a isIn r", "b isIn r", "c isIn r"])
    [(ended, reason)] = g.topics.tick()
    assert ended.failed and "more than 2 rows" in reason and topic.closed
    g.kb.close()


def test_refusals_are_the_hubs(graph: Graph) -> None:
    with pytest.raises(KbError, match="toto"):
        graph.topics.subscribe(["toto"], False, None)
    small = Graph(max_listeners=1)
    small.topics.subscribe(["?a sees ?b"], False, None)
    assert small.topics.subscribe(["?a sees ?b"], False, None) is not None  # shared: no new place taken
    with pytest.raises(ApiError) as refused:
        small.topics.subscribe(["?a likes ?b"], False, None)
    assert refused.value.status == 429 and len(small.topics) == 1
    small.kb.close()


def test_closing_ends_every_topic(graph: Graph) -> None:
    topics = [graph.subscribe(f"?x isIn room_{n}") for n in range(3)]
    graph.topics.close()
    assert all(t.closed for t in topics) and graph.hub.listener_count == 0


def test_a_topic_publishes_nothing_once_closed() -> None:
    topic = FakeTopic("evt_x")
    made = EventTopic("evt_x", topic, HOLD, Clock())
    topic.count = 1
    made.close()
    made.push([{"x": 1}])
    assert topic.sent == [] and made.tick() == "closed"


class CountingTopics(EventTopics):
    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.ticks = 0

    def tick(self) -> list[tuple[EventTopic, str]]:
        self.ticks += 1
        return super().tick()


def wait_for(condition: Callable[[], bool], timeout: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and not condition():
        time.sleep(0.005)
    return condition()


def test_the_sweeper_publishes_held_triggers_soon_and_sleeps_when_there_is_nothing_to_do() -> None:
    kb = KB()
    made: list[FakeTopic] = []

    def make(sub_id: str) -> FakeTopic:
        made.append(FakeTopic(sub_id))
        return made[-1]

    topics = CountingTopics(EventHub(kb, max_listeners=4), make, HOLD)
    sweeper = Sweeper(topics, fast=0.01, slow=60.0)
    sweeper.start()
    try:
        time.sleep(0.2)
        assert topics.ticks == 1  # no topic: asleep after its first look
        topics.subscribe(["?x isIn kitchen"], False, None)
        kb.add("cup_1 isIn kitchen")  # held: nobody has subscribed yet
        [topic] = made
        threading.Timer(0.1, lambda: setattr(topic, "count", 1)).start()  # the client is discovered
        assert wait_for(lambda: topic.sent == [[{"x": "cup_1"}]])
        settled = topics.ticks
        time.sleep(0.2)
        assert topics.ticks - settled <= 1  # nothing held: no more fast sweeps
    finally:
        sweeper.stop()
        topics.close()
        kb.close()
