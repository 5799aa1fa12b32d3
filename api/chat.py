"""``situated chat``: a conversation in a terminal, in-process or against a running service (``--url``).

Started without ``--user`` and reading its lines (not ``--say``), the robot greets and asks the
person's name; the answer makes them the speaker (`dialogue.sessions.introductions`: a person of the
KB called so, else a new one) and is their first turn. One Ctrl-C, or the end of input, ends the conversation.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import signal
import sys
import threading
from collections.abc import Awaitable, Callable, Iterator
from contextlib import AbstractContextManager
from typing import Any

from api.client import ServiceClient
from api.settings import load_settings
from dialogue.history import ASSISTANT_USER_ID
from dialogue.intents import UNKNOWN_AGENT
from dialogue.sessions.introductions import again, opening, speaker_named, told_name
from dialogue.understanding.language import Language

#: One turn: (speaker, text) -> the reply as the REST API shapes it.
Interact = Callable[[str, str], Awaitable[dict[str, Any]]]


def show(reply: dict[str, Any]) -> None:
    print(f"robot: {reply['response']}")
    if reply.get("dialogue_terminal") and reply.get("results") is not None:  # a leave-taking has none
        print(f"  results: {reply['results']}")
    for intent in reply["intents"]:
        print(f"  intent {intent['intent']} {json.dumps(intent['data'], ensure_ascii=False)} "
              f"(confidence {intent['confidence']})")
    if reply.get("error_msg"):
        print(f"  error: {reply['error_msg']}")


def lines(args: argparse.Namespace) -> Iterator[str]:
    if args.say:  # blank ones are no turn, as blank lines are not
        yield from (text.strip() for text in args.say if text.strip())
        return
    interactive = sys.stdin.isatty()
    while True:
        if interactive:
            print("you: ", end="", flush=True)
        line = sys.stdin.readline()
        if not line:
            return
        if line.strip():
            yield line.strip()


def _introduced(args: argparse.Namespace) -> bool:
    """Whether the robot asks who is speaking: no --user, lines read (not --say), the default role."""
    return args.user is None and not args.say and args.ask is None


def run(args: argparse.Namespace, open_kb: Callable[[argparse.Namespace], AbstractContextManager[Any]],
        say: Callable[[str], None]) -> int:
    if not args.say:
        where = args.url or f"an in-process KB (scene: {args.scene})"
        who = "whoever you say you are" if _introduced(args) else (args.user or UNKNOWN_AGENT)
        say(f"situated chat: talking to {where} as {who}; one line per turn; "
            "Ctrl-D (end of input) or Ctrl-C to leave")
    try:
        return asyncio.run(_converse(args, open_kb))
    except KeyboardInterrupt:
        say("")  # leave the terminal on a fresh line after the prompt
        return 0


def _role(args: argparse.Namespace) -> tuple[str, str]:
    """The dialogue's role and configuration: __ask__ with --ask and --field, else the default."""
    from dialogue.ask.form import ASK_ROLE, AskError, configuration_of

    if args.ask is None:
        if args.field:
            raise AskError("--field needs --ask QUESTION")
        return "__default__", "{}"
    if not args.field:
        raise AskError("--ask needs at least one --field NAME:TYPE")
    return ASK_ROLE, configuration_of(args.ask, args.field)


async def _converse(args: argparse.Namespace,
                    open_kb: Callable[[argparse.Namespace], AbstractContextManager[Any]]) -> int:
    if threading.current_thread() is threading.main_thread():
        # asyncio.run's own handler only cancels the main task at the first Ctrl-C, which waits for
        # the line being read: a second one was needed. Interrupt at once, wherever the chat waits.
        signal.signal(signal.SIGINT, signal.default_int_handler)
    role, configuration = _role(args)
    if args.url:
        with ServiceClient(args.url, args.token or os.environ.get("SITUATED_TOKEN")) as client:
            started = client.start_role(role, configuration, args.locale)

            async def remote(user: str, text: str) -> dict[str, Any]:
                # On the loop: the chat does nothing else meanwhile, and Ctrl-C need not wait for a thread.
                return client.interact(started["dialogue_id"], user, text)

            await _talk(args, client, started.get("response", ""), remote)
        return 0
    from api.services import build_dialogues

    settings = load_settings(llm=args.llm, scene=args.scene)
    with open_kb(args) as kb:
        dialogues = build_dialogues(settings, kb)
        try:
            dialogue = await dialogues.start_async(role, args.locale, configuration)

            async def local(user: str, text: str) -> dict[str, Any]:
                result = await dialogues.interact(user, text, dialogue_id=dialogue.id)
                return {"response": result.response, "intents": [i.model_dump() for i in result.intents],
                        "error_msg": result.error_msg, "dialogue_terminal": result.dialogue_terminal,
                        "results": result.results}

            await _talk(args, kb, dialogues.opening_line(dialogue), local)
        finally:
            await dialogues.engine.model.aclose()  # its HTTP client or worker process
    return 0


async def _talk(args: argparse.Namespace, people: Any, opening_line: str, interact: Interact) -> None:
    """The conversation: the role's opening line, who is speaking, then one turn per line."""
    if opening_line:
        print(f"robot: {opening_line}")
    said = lines(args)
    speaker = await _introduce(said, people, interact) if _introduced(args) else (args.user or UNKNOWN_AGENT)
    if speaker is None:
        return
    for text in said:
        reply = await interact(speaker, text)
        show(reply)
        if reply.get("dialogue_terminal"):
            break


async def _introduce(said: Iterator[str], people: Any, interact: Interact) -> str | None:
    """The robot asks the name until an answer gives one; that answer is the speaker's first turn.
    None: the input ended first. The questions go into the dialogue's history as the robot's words,
    so the rules read the answer as the speaker's name."""
    english = Language.load("en")  # the offline rules read English
    question = opening(english)
    while True:
        print(f"robot: {question}")
        await interact(ASSISTANT_USER_ID, question)
        text = next(said, None)
        if text is None:
            return None
        name = told_name(english, text)
        if name:
            speaker = speaker_named(people, name)  # a few KB reads, nothing else to do meanwhile
            show(await interact(speaker, text))
            return speaker
        question = again(english)
