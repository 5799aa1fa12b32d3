"""The client side of `situated bench ros`: a plain rclpy node in its own process that times the same
dialogue turn over ROS (DialogueInteraction) and over HTTP, and the same query over ROS (kb_msgs
Query) and REST (``/kb/query``), sequential calls after a warm-up. Driven by bench.ros over its
stdin, one block at a time (so that the blocks of every transport, and the in-process ones bench.ros
times between them, share the machine's ups and downs): each line ``N`` times N calls of each and
prints one JSON line, ``{name: [seconds, ...]}``; an empty line or end of input ends it. Run in ROS's
environment: ``python -m bench.rosclient --url URL``; rclpy is imported only then.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from collections.abc import Callable
from typing import Any

import httpx

from bench.http import no_delay

#: The turn and the query each transport carries (bench.ros's scene).
SPEAKER, UTTERANCE = "person_alice", "pick up the cup"
PATTERNS = ["myself sees ?o"]
WARM_UP = 20


def timed(call: Callable[[], None], count: int) -> list[float]:
    latencies: list[float] = []
    for _ in range(count):
        before = time.perf_counter()
        call()
        latencies.append(time.perf_counter() - before)
    return latencies


#: The client's executor: rclpy's EventsExecutor (the middleware's events, as the service's node) or
#: its SingleThreadedExecutor (a wait set rebuilt in Python per spin).
EXECUTORS = ("events", "single")


class Ros:
    """One node; a call spins it in the calling thread until the response is there (as a
    synchronous client does: no thread hands the response over)."""

    def __init__(self, executor: str) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.experimental.events_executor import EventsExecutor

        rclpy.init()
        self.node = rclpy.create_node("situated_bench_client")
        self.executor = EventsExecutor() if executor == "events" else SingleThreadedExecutor()
        self.executor.add_node(self.node)

    def caller(self, kind: Any, name: str, request: Any,
               check: Callable[[Any], None] = lambda response: None) -> Callable[[], None]:
        """A call of service ``name`` with ``request``, whose response ``check`` sees."""
        client = self.node.create_client(kind, name)
        if not client.wait_for_service(timeout_sec=60):
            raise RuntimeError(f"{name} is not served")

        def call() -> None:
            future = client.call_async(request)
            self.executor.spin_until_future_complete(future, timeout_sec=30)
            if not future.done():
                raise RuntimeError(f"{name}: no answer in 30 s")
            check(future.result())

        return call


def has_intents(response: Any) -> None:
    if not response.intents:
        raise RuntimeError(f"the benchmark turn over ROS gave no intent: {response}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.rosclient", description=__doc__)
    parser.add_argument("--url", required=True)
    parser.add_argument("--executor", choices=EXECUTORS, default=EXECUTORS[0])
    args = parser.parse_args(argv)
    from chatbot_msgs.srv import DialogueInteraction
    from kb_msgs.srv import Query

    ros = Ros(args.executor)
    # The nil UUID: the service's default dialogue, the one the HTTP requests talk in too.
    turn = DialogueInteraction.Request(user_id=SPEAKER, input=UTTERANCE, response_expected=True)
    ros_turn = ros.caller(DialogueInteraction, "/chatbot/dialogue_interaction", turn, has_intents)
    ros_query = ros.caller(Query, "/kb/query", Query.Request(patterns=PATTERNS))
    with httpx.Client(timeout=30, transport=no_delay()) as http:
        def http_turn() -> None:
            answer = http.post(f"{args.url}/dialogues/default/interactions",
                               json={"user_id": SPEAKER, "input": UTTERANCE})
            answer.raise_for_status()

        def http_query() -> None:
            http.post(f"{args.url}/kb/query", json={"patterns": PATTERNS}).raise_for_status()

        calls = {"turn ros": ros_turn, "turn http": http_turn, "query ros": ros_query,
                 "query http": http_query}
        for call in calls.values():
            timed(call, WARM_UP)
        print(json.dumps({"ready": True}), flush=True)
        for line in sys.stdin:
            if not line.strip():
                break
            count = int(line)
            print(json.dumps({name: timed(call, count) for name, call in calls.items()}), flush=True)
    ros.executor.shutdown(timeout_sec=2)
    # rclpy's executor threads may still be winding down: leave without running their destructors
    # (a C++ std::thread destroyed while joinable aborts the process).
    os._exit(0)


if __name__ == "__main__":
    raise SystemExit(main())
