"""The ``situated`` command: serve, chat, kb, humans, eval, bench, doctor, data, ros. Thin over the libraries.

``kb``, ``humans`` and ``chat`` work in-process (a fresh KB, loaded with ``--scene``) or against a
running service with ``--url`` (token from ``--token`` or ``$SITUATED_TOKEN``); ``kb add`` and
``kb retract`` only with ``--url`` (in-process, what they change would be gone when they end).
"""

from __future__ import annotations

import argparse
import importlib
import json
import logging
import os
import sys
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any

from api.client import ClientError, ServiceClient
from api.guides import Guided, Kind, about, guide, listing, see
from api.humans import known_humans, render
from api.ros import cli as ros_cli
from api.settings import SettingsError, load_settings
from dialogue.errors import DialogueError
from dialogue.trace.urlsecrets import redact
from kb import KB, KbError
from kb.datadir import check as check_data
from kb.datadir import repair as repair_data
from kb.errors import DataCorrupt
from kb.rdfio import parse_location
from scene.world import check_scene, load_any_scene

if TYPE_CHECKING:
    from api.app import Extension

BENCHES = ("kb", "scene", "dialogue", "grounding", "startup", "http", "load", "store", "backend")
#: Not in `all`: model needs the optional local model (the `local` extra) and takes minutes; ros
#: needs ROS 2 (a sourced environment, or --prefix DIR built by `situated ros install`); soak runs
#: for as many minutes as it is asked (an hour by default).
OPTIONAL_BENCHES = ("model", "ros", "soak")
# tests/api/test_cli.py runs every example below, so they cannot drift from what works.
KITCHEN = "tests/dialogue/eval/scenes/kitchen.txt"
EXAMPLES = f"""examples (file paths are those of a clone of the repository):
  situated serve                                     offline service on 127.0.0.1:8000 with the demo scene
  situated serve --scene {KITCHEN} --data ./data
                                                     a statements file; every write journaled in ./data
  situated serve --llm ollama:gemma3:1b --token T    with a local LLM; writes need 'Bearer T'
  situated chat --scene {KITCHEN}
                                                     talk in-process (one line per turn)
  situated chat --url http://127.0.0.1:8000 --say "pick up the cup"
  situated chat --ask "How old are you, and which cup?" --field age:integer --field cup:dbr:Cup
                                                     an ask dialogue: the answers fill the fields
  situated kb query "myself sees ?o" "?o rdf:type dbr:Cup" --scene {KITCHEN}
  situated kb add "cup_1 isOn table_1" --url http://127.0.0.1:8000
  situated kb retract "?x isOn table_1" --url http://127.0.0.1:8000
  situated kb details cup_1 --scene {KITCHEN}
  situated kb lookup cookbook --scene {KITCHEN}
  situated humans --url http://127.0.0.1:8000        id, name, seen, engagement
  situated eval tests/dialogue/eval/dev.jsonl --llm rules --json
                                                     score dialogue cases
  situated bench kb --quick                          small sizes; also scene, dialogue, grounding, http...
  situated doctor                                    check the setup (also --llm SPEC); exit 1 on a problem
  situated data check ./data                         is the journal/snapshot intact? (exit 1 if damaged)
  situated data repair ./data                        keep every intact record; damaged files kept beside
Each command has its own help: situated COMMAND -h.
Settings also come from SITUATED_* env vars and a TOML/JSON file (SITUATED_CONFIG or --config).
An error names the guide that explains it."""


# kb subcommand: what it does, its argument, an example of the argument (run by the tests).
KB_COMMANDS = {
    "query": ("rows matching patterns (a conjunction)", "patterns", '"myself sees ?o" "?o rdf:type dbr:Cup"'),
    "add": ("add statements (no variables)", "statements", '"cup_1 isOn shelf_1"'),
    "retract": ("retract statements (variables allowed)", "statements", '"?x isOn table_1"'),
    "details": ("details of a term", "term", "cup_1"),
    "lookup": ("find terms by name or label", "text", "cookbook"),
}


#: kb commands that change the KB: in-process, the KB they would change is gone when they end.
KB_WRITES = ("add", "retract")
#: The namespace attribute holding the parser of the command given (its usage, for its errors).
_PARSER = "_command_parser"


class CommandError(Exception):
    """A command line that cannot do what it asks; the message says why and what to give instead."""


def _say(text: str) -> None:
    print(text, file=sys.stderr)


def _ontology_option(parser: argparse.ArgumentParser, where: str = "") -> None:
    parser.add_argument("--ontology", action="append", type=Path, metavar="FILE",
                        help=f"{where}an extra OWL/RDF file (.ttl, .rdf/.owl, .nt; repeatable) loaded into "
                             "the KB before the scene and reasoned with it (default: the settings' "
                             "ontology_files)")


def _remote_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--url", help="a running service, e.g. http://127.0.0.1:8000 (default: in-process)")
    parser.add_argument("--token", help="bearer token for --url (default: $SITUATED_TOKEN)")
    parser.add_argument("--scene", default="demo", help="in-process: the scene to load first: demo "
                        "(default), an .svg/.json scene, a .txt file of statements, or none")
    _ontology_option(parser, "in-process: ")


def _serve_options(serve: argparse.ArgumentParser) -> None:
    serve.add_argument("--host", help="interface to bind (default 127.0.0.1)")
    serve.add_argument("--port", type=int, help="port (default 8000)")
    serve.add_argument("--data", type=Path, help="data folder: every write journaled, recovered at start")
    serve.add_argument("--scene", help="demo (default), an .svg environment, a .json scene, a .txt file of "
                                       "statements, or none")
    _ontology_option(serve)
    serve.add_argument("--llm", help="model backend: rules (default), ollama:MODEL[@URL], openai:MODEL@URL, "
                                     "openai-json:MODEL@URL (llama.cpp's server), llamacpp:PATH.gguf or "
                                     "llamacpp:smollm2 (the 'local' extra; '?threads=N' for N llama.cpp "
                                     "threads), hybrid:SPEC (rules first, the model SPEC only when they do "
                                     "not understand)")
    serve.add_argument("--token", help="require 'Authorization: Bearer TOKEN' for writes")
    serve.add_argument("--config", type=Path, help="TOML or JSON settings file (or $SITUATED_CONFIG)")
    serve.add_argument("--store", help="keep the KB in a SPARQL 1.1 store, e.g. "
                                       "sparql+http://127.0.0.1:7878 (the writer, unless --writer is given)")
    serve.add_argument("--writer", help="with --store: be a reader; writes go to the writer service here")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="situated", description=__doc__,
                                     epilog=f"{EXAMPLES}\n\nguides (docs/ in a clone):\n{listing()}",
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    serve = sub.add_parser("serve", help="run the HTTP service (default 127.0.0.1:8000, rules backend)")
    serve.set_defaults(**{_PARSER: serve})
    _serve_options(serve)

    chat = sub.add_parser("chat", help="talk to the robot (in-process or --url), showing reply and intents")
    chat.set_defaults(**{_PARSER: chat})
    _remote_options(chat)
    chat.add_argument("--llm", default="rules", help="in-process model backend, as for serve (default rules)")
    chat.add_argument("--user", help="speaker id, known or new (e.g. person_bob); default: the robot asks "
                      "your name (with --say or --ask: __unknown_agent__, nobody)")
    chat.add_argument("--say", action="append", help="say this and exit (repeatable); default: read stdin")
    chat.add_argument("--ask", metavar="QUESTION", help="start an ask dialogue (the __ask__ role) with this "
                      "question; it ends when its --field values are obtained")
    chat.add_argument("--field", action="append", default=[], metavar="NAME:TYPE",
                      help="a field of --ask (repeatable): TYPE is boolean, integer, number, string, person, "
                           "thing, place, entity, a KB class (cup:dbr:Cup) or values (size:s|m|l)")
    chat.add_argument("--locale", help="the dialogue's locale, ll_CC (e.g. en_GB, fr_FR)")

    kb = sub.add_parser("kb", help="query and edit the KB: query, add, retract, details, lookup (add and "
                                   "retract: of a running service, --url)")
    kb_sub = kb.add_subparsers(dest="kb_command", required=True, metavar="KB_COMMAND")
    for name, (what, arg, example) in KB_COMMANDS.items():
        one = kb_sub.add_parser(name, help=what)
        one.set_defaults(**{_PARSER: one})
        many = "+" if arg in ("patterns", "statements") else None
        one.add_argument(arg, nargs=many, help=f"e.g. {example}")
        one.add_argument("--models", nargs="*", help="KB models (default: the robot's own)")
        _remote_options(one)

    humans = sub.add_parser("humans", help="persons the KB knows: id, name, seen, engagement")
    humans.set_defaults(**{_PARSER: humans})
    _remote_options(humans)

    evaluate = sub.add_parser("eval", help="score dialogue cases (.jsonl); see 'situated eval -h'",
                              add_help=False)
    evaluate.add_argument("args", nargs=argparse.REMAINDER, help="passed to the evaluation")

    doctor = sub.add_parser("doctor", help="check the setup (KB, data folder, model backend, Chromium, "
                                           "port); exit 1 on a problem")
    for option in ("--llm", "--scene", "--host"):
        doctor.add_argument(option, help=f"as for serve (default: the settings' {option[2:]})")
    doctor.add_argument("--ontology", action="append", type=Path, metavar="FILE",
                        help="as for serve (default: the settings' ontology_files)")
    doctor.add_argument("--port", type=int, help="as for serve (default: the settings' port)")
    doctor.add_argument("--data", type=Path, help="as for serve (default: the settings' data folder)")
    doctor.add_argument("--config", type=Path, help="TOML or JSON settings file (or $SITUATED_CONFIG)")
    doctor.add_argument("--strict", action="store_true", help="warnings (no Chromium) also exit 1")
    doctor.set_defaults(**{_PARSER: doctor})
    data = sub.add_parser("data", help="check or repair a data folder (DIR): journal and snapshot")
    data.add_argument("action", choices=["check", "repair"], help="check: report, exit 1 if damaged; "
                      "repair (service stopped): keep every intact record, the damaged files beside them")
    data.add_argument("dir", type=Path, help="the data folder")
    data.set_defaults(**{_PARSER: data})

    bench = sub.add_parser("bench", help="run benchmarks: " + ", ".join(BENCHES) + ", all (those), "
                                         "model (the local LLM path; the local extra), ros (over ROS 2 "
                                         "beside HTTP and in process; --prefix DIR) or soak (the service "
                                         "over --minutes N)")
    bench.add_argument("which", nargs="?", default="all", choices=[*BENCHES, *OPTIONAL_BENCHES, "all"])
    bench.set_defaults(**{_PARSER: bench})
    bench.add_argument("args", nargs=argparse.REMAINDER, help="passed to the benchmark")
    ros_cli.add_parser(sub, _serve_options)
    return parser


# --- serve -----------------------------------------------------------------------------------------

def _serve(args: argparse.Namespace) -> int:
    _run_service(args)
    return 0


def _run_service(args: argparse.Namespace, extensions: Sequence[Extension] = (), also: str = "") -> None:
    """Serve with ``serve``'s options in ``args``; ``extensions``: other fronts in the same process
    (``situated ros run``), ``also`` what the start-up line says of them."""
    import uvicorn

    from api.accesslog import log_config
    from api.app import create_app
    from api.services import backend_of

    settings = load_settings(args.config, host=args.host, port=args.port, data_dir=args.data,
                             scene=args.scene, llm=args.llm, token=args.token, store=args.store,
                             writer_url=args.writer, ontology_files=args.ontology)
    backend_of(settings)  # a bad backend spec is reported before anything starts
    with about(Kind.SCENES):
        if settings.role != "reader":  # a reader ignores them: they are the writer's
            for path in settings.ontology_files:  # a file that does not parse, too
                parse_location(str(path))
        check_scene(settings.scene)  # so is a scene that cannot be loaded (else: a start-up traceback)
    if settings.data_dir is not None:
        _make_data_dir(settings.data_dir)  # and a data folder that cannot be made
    if settings.data_dir is not None and settings.data_dir.is_dir():
        report = check_data(settings.data_dir)  # damage is reported plainly, not as a traceback
        if report.damaged:
            raise DataCorrupt(report.render())
    # Start-up progress (journal recovery, ontology files, the scene) is logged by situated.*.
    logging.basicConfig(level=logging.INFO, format="%(levelname)s:     %(name)s: %(message)s")
    role = "" if settings.role == "standalone" else f"; {settings.role} of {settings.store}"
    _say(redact(f"situated: serving on http://{settings.host}:{settings.port}{also} (model: {settings.llm}; "
                f"scene: {settings.scene or 'none'}{role}); loading the KB..."))
    uvicorn.run(create_app(settings, extensions=extensions), host=settings.host, port=settings.port,
                ws="websockets-sansio", ws_max_size=settings.limits.max_body_bytes, log_level="info",
                log_config=log_config())


def _make_data_dir(path: Path) -> None:
    if path.exists() and not path.is_dir():
        raise Guided(Kind.KB, CommandError(f"data folder '{path}' is not a folder: give --data a folder "
                                           "(made if missing)"))
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise Guided(Kind.KB, CommandError(f"cannot make data folder '{path}': {exc.strerror}")) from None


# --- KB access, in-process or remote ----------------------------------------------------------------

@contextmanager
def _kb(args: argparse.Namespace) -> Iterator[Any]:
    if args.url:
        with ServiceClient(args.url, args.token or os.environ.get("SITUATED_TOKEN")) as client:
            yield client
        return
    _say("loading the KB...")
    ontologies = load_settings(ontology_files=args.ontology).ontology_files
    with KB() as kb:
        with about(Kind.SCENES):
            for path in ontologies:  # before the scene, as a service loads them
                kb.load(str(path))
                _say(f"loaded the ontology file {path}")
            if args.scene and args.scene != "none":
                _say(load_any_scene(kb, args.scene))
        yield kb


def _print_json(value: Any) -> None:
    print(json.dumps(value, indent=2, ensure_ascii=False))


def _kb_command(args: argparse.Namespace) -> int:
    if args.kb_command in KB_WRITES and not args.url:
        raise Guided(Kind.KB, CommandError(
            f"{args.kb_command} changes the KB of a running service: give its --url (e.g. --url "
            "http://127.0.0.1:8000); without it the change would go to a throwaway in-process KB, gone "
            "when the command ends"))
    models = args.models or None
    with _kb(args) as kb:
        command = args.kb_command
        if command == "query":
            _print_json(_find(kb, args.patterns, models))
        elif command == "add":
            kb.revise(args.statements, {"method": "update", "models": models})
            _say(f"add: {len(args.statements)} statement(s)")
        elif command == "retract":
            # One pattern may match many triples: say what went, not what was asked.
            removed = kb.revise(args.statements, {"method": "retract", "models": models})
            _say(f"retract: {removed} triple(s) removed")
        elif command == "details":
            _print_json(kb.details(args.term, models))
        else:
            _print_json(kb.lookup(args.text, models))
    return 0


def _find(kb: KB | ServiceClient, patterns: list[str], models: list[str] | None) -> list[Any]:
    if isinstance(kb, ServiceClient):  # the service applies its own limits
        return kb.find(patterns, None, models)
    limits = load_settings().limits  # in-process, the same limits as the service's settings
    return kb.find(patterns, None, models, max_rows=limits.max_rows, timeout=limits.query_timeout)


def _humans(args: argparse.Namespace) -> int:
    with _kb(args) as kb:
        print(render(known_humans(kb)))
    return 0


# --- chat ------------------------------------------------------------------------------------------

def _chat(args: argparse.Namespace) -> int:
    from api.chat import run

    return run(args, _kb, _say)


# --- data ------------------------------------------------------------------------------------------

def _data(args: argparse.Namespace) -> int:
    report = repair_data(args.dir) if args.action == "repair" else check_data(args.dir)
    print(report.render())
    return 1 if report.damaged and args.action == "check" else 0


# --- eval and bench --------------------------------------------------------------------------------

def _eval(args: argparse.Namespace) -> int:
    from dialogue.evaluation.command import main as evaluate

    return evaluate(args.args, guide=guide(Kind.EVALUATION))


def _split_eval(argv: Sequence[str] | None) -> list[str] | None:
    """``eval``'s own arguments (its options included, which argparse's REMAINDER would refuse)."""
    words = list(sys.argv[1:] if argv is None else argv)
    return words[1:] if words[:1] == ["eval"] else None


def _bench(args: argparse.Namespace) -> int:
    status = 0
    for name in BENCHES if args.which == "all" else (args.which,):
        try:
            module = importlib.import_module(f"bench.{name}")
        except ModuleNotFoundError as exc:
            _say(f"situated bench {name}: benchmark module bench.{name} is not available ({exc}; see "
                 f"{guide(Kind.BENCHMARKS)})")
            status = 1
            continue
        if hasattr(module, "main"):
            status |= int(module.main(list(args.args)))
        else:
            print(module.run())
    return status


def _doctor(args: argparse.Namespace) -> int:
    from api.doctor import Doctor, exit_status, render

    settings = load_settings(args.config, host=args.host, port=args.port, data_dir=args.data,
                             scene=args.scene, llm=args.llm, ontology_files=args.ontology)
    findings = Doctor(settings).run()
    print(render(findings))
    return exit_status(findings, args.strict)


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {
    "serve": _serve, "chat": _chat, "kb": _kb_command, "humans": _humans, "eval": _eval, "bench": _bench,
    "doctor": _doctor,
    "data": _data,
    "ros": lambda args: ros_cli.command(args, _run_service),
}


def main(argv: Sequence[str] | None = None) -> int:
    eval_args = _split_eval(argv)
    if eval_args is not None:
        return _eval(argparse.Namespace(command="eval", args=eval_args))
    parser = _parser()
    args, unknown = parser.parse_known_args(argv)
    if unknown:  # said with the usage of the command given, not the top-level one
        getattr(args, _PARSER, parser).error(f"unrecognized arguments: {' '.join(unknown)}")
    try:
        return COMMANDS[args.command](args)
    except (KbError, ClientError, SettingsError, DialogueError, ros_cli.RosError, CommandError,
            Guided) as exc:
        _say(f"situated {args.command}: {exc}{see(exc)}")
        return 2


if __name__ == "__main__":
    sys.exit(main())
