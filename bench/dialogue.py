"""Dialogue turn overhead, excluding the model: `python -m bench.dialogue` (or `run()` -> table).

Scene: the kitchen with 100 visible objects. Measured per turn (median over many turns):
- overhead (warm): grounding from the per-revision snapshot cache, the turn's JSON schema, prompt
  rendering, then validation and resolution of a model answer;
- overhead (KB changed): the same when the KB revision changed since the last turn, so that the
  snapshot is rebuilt from KB queries first;
- rules fast path: interpreting the utterance with the rules and grounding the result;
- full rules turn: `await engine.turn(...)` through the event loop.
Target: <= 2 ms median for the warm overhead and the rules fast path. Each row gives the median
wall time and the median CPU time (the process's) of a turn: on a shared machine the wall time
waits for a core, the CPU time much less.
"""

from __future__ import annotations

import asyncio
import os
import statistics
import time
from collections.abc import Callable

from bench.progress import step
from dialogue.engine import DialogueEngine
from dialogue.schema import parse_answer
from dialogue.validate import ground_answer
from kb import KB

SCENE = [
    "myself rdf:type Robot", "kitchen rdf:type ZoneOfInterest", 'kitchen rdfs:label "kitchen"',
    "person_alice rdf:type Human", 'person_alice rdfs:label "Alice"', "myself sees person_alice",
    "table_1 rdf:type dbr:Table_(furniture)", "table_1 isIn kitchen", "myself sees table_1",
    "shelf_1 rdf:type dbr:Shelf_(storage)", "shelf_1 isIn kitchen", "myself sees shelf_1",
]  # fmt: skip
CLASSES = ["dbr:Cup", "dbr:Book", "dbr:Apple", "dbr:Smartphone", "dbr:Pear"]
COLOURS = ["red", "blue", "green", "white", "black"]


def label(i: int) -> str:
    """The label of object i of the scene ("blue apple 7"), so that utterances name what it has."""
    klass, colour = CLASSES[i % len(CLASSES)], COLOURS[(i // len(CLASSES)) % len(COLOURS)]
    return f"{colour} {klass.split(':')[1].lower().replace('smartphone', 'phone')} {i}"


UTTERANCES = [
    f"pick up the {label(7)}",
    f"bring me the {label(12)}",
    f"put the {label(3)} on the shelf",
    "go to the kitchen",
    f"where is the {label(9)}?",
    "hello",
    "what do you see?",
    "grab the cup",  # several cups: a clarifying question
    f"um take the {label(20)} and put it on the table",  # compound, speech style
    f"grab the heavy {label(33)} from the cupboard",  # modifiers the KB cannot check
]
ANSWER = '{"verbal_ack": "OK", "user_intent": {"type": "__intent_grab_object__", "object": "obj_042"}}'


def scene(n_objects: int = 100) -> KB:
    kb = KB()
    facts = list(SCENE)
    for i in range(n_objects):
        oid = f"obj_{i:03d}"
        facts += [
            f"{oid} rdf:type {CLASSES[i % len(CLASSES)]}",
            f'{oid} rdfs:label "{label(i)}"',
            f"{oid} isOn {'table_1' if i % 2 else 'shelf_1'}",
            f"{oid} isIn kitchen",
            f"myself sees {oid}",
        ]
    kb.update(facts)
    return kb


def _clocks() -> tuple[float, float]:
    return time.perf_counter(), time.process_time()


def medians(fn: Callable[[], object], repeat: int) -> tuple[float, float]:
    """Median wall and CPU ms of `fn`, over `repeat` calls."""
    wall, cpu = [], []
    for _ in range(repeat):
        start, start_cpu = _clocks()
        fn()
        end, end_cpu = _clocks()
        wall.append(end - start)
        cpu.append(end_cpu - start_cpu)
    return statistics.median(wall) * 1000, statistics.median(cpu) * 1000


def run(n_objects: int = 100, repeat: int = 200) -> str:
    step("dialogue", f"a scene of {n_objects} visible objects")
    kb = scene(n_objects)
    engine = DialogueEngine(kb)
    speaker = "person_alice"

    def overhead() -> None:
        grounded = engine.ground()
        turn = engine.prepare(grounded, f"grab the {label(42)}", speaker, (), None)
        engine.schema_for(grounded[0], speaker)
        engine.prompts.messages(turn.context)
        ground_answer(parse_answer(ANSWER), turn.lexicon, speaker)

    counter = iter(range(1, 10**9))

    def overhead_changed() -> None:  # includes the KB write itself (small next to the rebuild)
        # hasColor is functional: alternating colours changes the KB (and its revision) every time.
        before = kb.revision
        kb.update([f"obj_000 hasColor {'yellow' if next(counter) % 2 else 'pink'}"])
        assert kb.revision != before
        overhead()

    utterances = iter(UTTERANCES * (repeat * 2))

    def fast_path() -> None:
        engine.fast_path(engine.prepare(engine.ground(), next(utterances), speaker, (), None))

    async def turns() -> tuple[float, float]:
        wall, cpu = [], []
        for i in range(repeat):
            start, start_cpu = _clocks()
            await engine.turn(UTTERANCES[i % len(UTTERANCES)], speaker=speaker)
            end, end_cpu = _clocks()
            wall.append(end - start)
            cpu.append(end_cpu - start_cpu)
        return statistics.median(wall) * 1000, statistics.median(cpu) * 1000

    overhead()  # warm caches
    step("dialogue", f"turn overhead, {repeat} rounds")
    rows = [("overhead, warm (ground+schema+prompt+validate+resolve)", medians(overhead, repeat))]
    step("dialogue", "turn overhead right after a KB change")
    rows.append(("overhead, KB changed since last turn (snapshot rebuilt)",
                 medians(overhead_changed, max(20, repeat // 10))))
    step("dialogue", "rules fast path")
    rows.append(("rules fast path", medians(fast_path, repeat)))
    step("dialogue", "full rules turns through the event loop")
    rows.append(("full rules turn (engine.turn, event loop)", asyncio.run(turns())))
    kb.close()
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    lines = [f"dialogue turn overhead, {n_objects} visible objects (median ms; target <= 2 ms;"
             f" load average {load})", f"  {'':58} {'wall':>8} {'cpu':>8}"]
    lines += [f"  {name:58} {wall:8.3f} {cpu:8.3f}" for name, (wall, cpu) in rows]
    return "\n".join(lines)


if __name__ == "__main__":
    print(run())
