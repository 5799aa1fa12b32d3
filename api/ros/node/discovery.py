"""Per-person and per-voice topics (ROS4HRI's ``/humans/persons/<id>/...``, ``/humans/voices/<id>/...``)
as they appear on the graph and go.

ROS4HRI makes a topic per tracked person or voice: no single topic lists them all. A watch looks at
the graph's topics every ``period`` seconds; a topic whose name matches and that someone publishes
is handed to ``appeared`` (with the id the pattern's group takes), which returns what it made of it
(a subscription); once nobody publishes it any more, ``gone`` gets that back (our own subscription
keeps the topic on the graph: publishers are what tell).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

#: Seconds between two looks at the graph.
PERIOD = 0.5


class TopicWatch:
    def __init__(self, node: Any, pattern: str, appeared: Callable[[str, str], Any],
                 gone: Callable[[str, str, Any], None], group: Any, period: float = PERIOD) -> None:
        self.node = node
        self.pattern = re.compile(pattern)
        self.appeared = appeared
        self.gone = gone
        #: What `appeared` made of each topic watched, by topic name.
        self.watched: dict[str, tuple[str, Any]] = {}
        self.timer = node.create_timer(period, self.look, callback_group=group)

    def look(self) -> None:
        published = set()
        for name, _types in self.node.get_topic_names_and_types():
            found = self.pattern.fullmatch(name)
            if found is not None and self.node.count_publishers(name) > 0:
                published.add(name)
                if name not in self.watched:
                    self.watched[name] = (found.group(1), self.appeared(found.group(1), name))
        for name in set(self.watched) - published:
            key, made = self.watched.pop(name)
            self.gone(key, name, made)

    def close(self) -> None:
        self.timer.cancel()
        self.node.destroy_timer(self.timer)
        for name, (key, made) in list(self.watched.items()):
            self.gone(key, name, made)
        self.watched.clear()
