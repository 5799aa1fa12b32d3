"""situated's dialogue engine: one grounded turn from words and the KB to a reply and ROS4HRI intents.

Public API (exported here, see ``__all__``; nothing is done at import time):

- `dialogue.engine.DialogueEngine(kb, model=None, config=EngineConfig(...))`, then
  `await engine.turn(text, speaker=user_id, history=[Utterance...], locale=None) -> TurnResult`
  (`response`, `intents` (dialogue.intents.Intent), `error_msg`, `backend`, `clarify`);
- `dialogue.sessions.manager.DialogueManager(engine, store=None)`: `start(role, locale)`, `get(id)`,
  `end(id)`, `ids()` (and their `*_async` forms for async code), `await interact(user_id, text,
  dialogue_id="default", locale=None, response_expected=True, history=None)`; errors are
  `SessionError` (`UnknownDialogue` for an id no dialogue has; every error of the package is a
  `DialogueError`); `store` is a
  `dialogue.sessions.store.SessionStore`: `MemorySessions` (default) or
  `dialogue.sessions.sparql.SparqlSessions(endpoint)` (shared by processes on one SPARQL store);
- `dialogue.llm.spec.parse_spec("rules" | "ollama:gemma3:1b[@URL]" | "openai:MODEL[@URL]" |
  "openai-json:MODEL[@URL]" | "hybrid:<llm spec>") -> Backend(model, spec)`; errors are `SpecError`;
  `dialogue.llm.hybrid.HybridModel(inner)` is what a `hybrid:` spec builds; `await model.aclose()`
  when done with a model;
- `dialogue.evaluation.cases.run(path, llm_spec) -> Report` (`score`, `claim_precision`);
  `dialogue.evaluation.command.main(argv)` is the `situated eval` command.

Modules: intents (Intent.msg catalogue), schema (answer models, per-turn JSON schema), situation
(snapshot as sentences), validate (model answer -> grounded intents), prompts, history, engine,
roles (default, ask), locales, speakers, errors; sessions/ (the dialogue manager; where dialogue
state lives, in memory or a SPARQL store; one turn at a time; which entries are answered; what a
role's state says; the observers told after each turn); ask/ (the __ask__ role's form), trace/
(every turn's record); reference/ (grounding: the KB snapshot; lexicon / resolution / clarify:
referents), understanding/ (words, commands, questions, answers, interpret: the offline rules), llm/
(backends), evaluation/ (the eval tool),
memory/ (what people tell the robot: claims, statements, learn, provenance, people), pushed/ (the
intent bus), initiative (engaging and greeting people).
"""

from dialogue.engine import DialogueEngine, EngineConfig, TurnResult
from dialogue.errors import DialogueError, SessionError, UnknownDialogue
from dialogue.history import Utterance
from dialogue.intents import Intent
from dialogue.llm.base import ChatModel, ModelError
from dialogue.llm.hybrid import HybridModel
from dialogue.llm.spec import SpecError, parse_spec
from dialogue.sessions.manager import DialogueManager

__all__ = [
    "ChatModel",
    "DialogueEngine",
    "DialogueError",
    "DialogueManager",
    "EngineConfig",
    "HybridModel",
    "Intent",
    "ModelError",
    "SessionError",
    "SpecError",
    "TurnResult",
    "UnknownDialogue",
    "Utterance",
    "parse_spec",
]
