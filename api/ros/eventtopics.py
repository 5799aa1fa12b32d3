"""knowledge_core's event topics (``/kb/events/<id>``), apart from rclpy: which triggers are
published, held or dropped, and when a topic ends.

knowledge_core 3.5 answers an Event request with the subscription's id and a topic, and publishes
each trigger's new rows there (a JSON list, as ``find`` returns them, in a std_msgs/String), but
only to a topic that has a subscriber at that moment: a client that has only just subscribed
(discovery takes a few tens of milliseconds) loses the first trigger. Here a trigger that finds
nobody yet is held, at most ``Hold.count`` of them (the oldest dropped), for at most
``Hold.seconds`` after the topic was last requested, and published in order as soon as a
subscriber is seen. Otherwise as knowledge_core: identical requests share one id and one topic,
and a topic that had a subscriber and has none left is ended (knowledge_core notices at the next
trigger; here also at the next sweep, so an abandoned topic gives its subscription back). A topic
also ends when nobody subscribed to it in time, once its one-shot trigger was delivered (after
``Hold.grace``, so that reliable delivery completes), when the KB ended its subscription (an
evaluation went past the query limits) and when the service stops.

Every topic's subscription is one of the event hub's (``api.subscriptions``): the same query limits
and the same subscriber limit as REST's event streams. A ``Sweeper`` thread ticks the topics: every
``FAST`` seconds while one holds triggers (a client is about to subscribe), every ``SLOW`` seconds
while there are topics, never when there are none (an idle node costs nothing).
"""

from __future__ import annotations

import json
import logging
import threading
import time
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

from api.subscriptions import EventHub

log = logging.getLogger("situated.ros")
#: Seconds between two sweeps while a topic holds triggers: they wait at most this long once
#: someone subscribed.
FAST = 0.02
#: Seconds between two sweeps otherwise: an abandoned topic is ended within about this long.
SLOW = 1.0


class Topic(Protocol):
    """One event topic of the middleware (an rclpy publisher, in the node)."""

    @property
    def name(self) -> str:
        """Its fully qualified name, as subscribers give it."""

    def subscribers(self) -> int: ...

    def publish(self, data: str) -> None: ...

    def close(self) -> None: ...


@dataclass(frozen=True)
class Hold:
    #: Triggers held for a topic nobody has subscribed to yet (past it, the oldest are dropped).
    count: int = 16
    #: Seconds a topic waits for its first subscriber after it was (last) requested.
    seconds: float = 30.0
    #: Seconds a one-shot topic stays once its trigger was published (reliable delivery completes).
    grace: float = 2.0


class EventTopic:
    """One subscription's topic: the hub's sink (``push``, ``fail``, ``end``: any thread) and the
    sweep's ``tick``. Its lock orders every publish and the closing of the topic."""

    def __init__(self, sub_id: str, topic: Topic, hold: Hold, clock: Callable[[], float],
                 held: Callable[[], None] = lambda: None) -> None:
        """``held`` is called (outside the lock) when a trigger is held."""
        self.sub_id = sub_id
        self.topic = topic
        self._hold = hold
        self._clock = clock
        self._on_held = held
        self._lock = threading.Lock()
        self._held: deque[str] = deque()
        self._dropped = 0
        self._requested = clock()
        self._listened = False  # a subscriber was seen
        self._spent = False  # its one-shot trigger came
        self._published = clock()
        self.ended: str | None = None
        self._closed = False
        self.failed = False  # ended by the KB (past the query limits), not by how it was used
        self.attached = True  # one of the hub's sinks

    @property
    def spent(self) -> bool:
        return self._spent

    @property
    def held(self) -> int:
        with self._lock:
            return len(self._held)

    # --- the hub's sink ---------------------------------------------------------------------------

    def push(self, rows: list[Any], last: bool = False) -> None:
        data = json.dumps(rows)
        with self._lock:
            if self.ended is not None:
                return
            self._spent = self._spent or last
            held = False
            if self.topic.subscribers() > 0:
                self._listened = True
                self._flush()
                self._publish(data)
            elif self._listened:
                self.ended = f"nobody listens to {self.topic.name} any more"
            else:
                if len(self._held) >= self._hold.count:
                    self._held.popleft()
                    self._dropped += 1
                self._held.append(data)
                held = True
        if held:
            self._on_held()

    def fail(self, error: dict[str, Any]) -> None:
        with self._lock:
            if self.ended is None:
                self.ended = f"its subscription was ended: {error.get('message', error)}"
                self.failed = True

    def end(self, reason: str) -> None:
        with self._lock:
            if self.ended is None:
                self.ended = reason

    # --- the registry's ---------------------------------------------------------------------------

    def rearm(self) -> bool:
        """Another request for this topic: its wait for a first subscriber starts again. False
        when it cannot be shared any more (ended, or its one-shot trigger came)."""
        with self._lock:
            if self.ended is not None or self._spent:
                return False
            self._requested = self._clock()
            return True

    def tick(self) -> str | None:
        """Publish what is held once someone subscribed; the reason the topic ends, if it does."""
        with self._lock:
            if self.ended is not None:
                return self.ended
            now = self._clock()
            if self.topic.subscribers() > 0:
                self._listened = True
                self._flush()
            elif self._listened:
                self.ended = f"nobody listens to {self.topic.name} any more"
            elif now - self._requested > self._hold.seconds:
                lost = len(self._held) + self._dropped
                self.ended = (f"nobody subscribed to {self.topic.name} within {self._hold.seconds:g} s"
                              + (f"; {lost} trigger(s) not delivered" if lost else ""))
            delivered = self._spent and not self._held
            if self.ended is None and delivered and now - self._published >= self._hold.grace:
                self.ended = "its one-shot trigger was published"
            return self.ended

    def close(self) -> None:
        with self._lock:
            self.ended = self.ended or "closed"
            self._held.clear()
            if not self._closed:
                self._closed = True
                self.topic.close()

    def _flush(self) -> None:
        if self._dropped:
            log.warning("event topic %s: %d early trigger(s) were dropped (at most %d are held until "
                        "someone subscribes)", self.topic.name, self._dropped, self._hold.count)
            self._dropped = 0
        while self._held:
            self._publish(self._held.popleft())

    def _publish(self, data: str) -> None:
        self.topic.publish(data)
        self._published = self._clock()


class EventTopics:
    """The node's event topics by subscription id, each on one of the hub's subscriptions."""

    def __init__(self, hub: EventHub, make_topic: Callable[[str], Topic], hold: Hold | None = None,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self._hub = hub
        self._make_topic = make_topic
        self._hold = hold or Hold()
        self._clock = clock
        self._lock = threading.Lock()
        self._topics: dict[str, EventTopic] = {}
        self._retiring: list[EventTopic] = []  # replaced by a newer topic of the same id, not closed yet
        #: Called when there is something for a sweep to do sooner (a new topic, a held trigger).
        self.changed: Callable[[], None] = lambda: None

    def __len__(self) -> int:
        with self._lock:
            return len(self._topics) + len(self._retiring)

    def holding(self) -> bool:
        """True while a topic holds triggers for a subscriber yet to come."""
        with self._lock:
            topics = [*self._topics.values(), *self._retiring]
        return any(topic.held for topic in topics)

    def subscribe(self, patterns: Sequence[str], one_shot: bool, models: Sequence[str] | None) -> EventTopic:
        """The topic of these patterns (an existing one, or a new subscription). The hub's errors
        as they are: ``ApiError`` past the subscriber limit, ``KbError`` (bad patterns, starting
        rows past the query limits)."""
        key = EventHub.key(patterns, one_shot, models)
        # Held across the hub's subscribe: two requests for one new id make one topic.
        with self._lock:
            current = self._topics.pop(key, None)
            if current is not None:
                if current.rearm():
                    self._topics[key] = current
                    return current
                self._retiring.append(current)
            made = self._hub.attach(list(patterns), one_shot, models, self._new)
            self._topics[made.sub_id] = made
        self.changed()
        return made

    def _new(self, sub_id: str) -> EventTopic:
        return EventTopic(sub_id, self._make_topic(sub_id), self._hold, self._clock, lambda: self.changed())

    def tick(self) -> list[tuple[EventTopic, str]]:
        """Publish held triggers, end the topics that are done; returns those ended, with why."""
        with self._lock:
            topics = [*self._topics.values(), *self._retiring]
        ended: list[tuple[EventTopic, str]] = []
        for topic in topics:
            reason = topic.tick()
            if reason is not None:
                ended.append((topic, reason))
            elif topic.spent:
                self._detach(topic)  # its subscription is over: free its place among the subscribers
        for topic, reason in ended:
            self._close(topic)
            (log.error if topic.failed else log.info)("event %s ended: %s", topic.sub_id, reason)
        return ended

    def close(self) -> None:
        """End every topic (the node stops)."""
        with self._lock:
            topics = [*self._topics.values(), *self._retiring]
        for topic in topics:
            self._close(topic)

    def _close(self, topic: EventTopic) -> None:
        with self._lock:
            if self._topics.get(topic.sub_id) is topic:
                del self._topics[topic.sub_id]
            if topic in self._retiring:
                self._retiring.remove(topic)
        self._detach(topic)
        topic.close()

    def _detach(self, topic: EventTopic) -> None:
        if topic.attached:
            topic.attached = False
            self._hub.close(topic)


class Sweeper:
    """The thread that ticks the topics: soon after a change, then every ``FAST`` seconds while one
    holds triggers, every ``SLOW`` seconds while there are topics; asleep when there are none."""

    def __init__(self, topics: EventTopics, fast: float = FAST, slow: float = SLOW) -> None:
        self._topics = topics
        self._fast, self._slow = fast, slow
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="ros-event-topics", daemon=True)
        topics.changed = self._wake.set

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        self._wake.set()
        self._thread.join(5)

    def _run(self) -> None:
        while not self._stop.is_set():
            self._wake.clear()
            self._topics.tick()
            if self._topics.holding():
                wait: float | None = self._fast
            else:
                wait = self._slow if len(self._topics) else None
            self._wake.wait(wait)
