"""situated's dialogue engine: one grounded turn from words and the KB to a reply and ROS4HRI intents.

Public API (import from the submodules; nothing is done at import time):

- `dialogue.engine.DialogueEngine(kb, model=None, config=EngineConfig(...))`, then
  `await engine.turn(text, speaker=user_id, history=[Utterance...], locale=None) -> TurnResult`
  (`response`, `intents` (dialogue.intents.Intent), `error_msg`, `backend`, `clarify`);
- `dialogue.sessions.DialogueManager(engine, store=None)`: `start(role, locale)`, `get(id)`, `end(id)`,
  `ids()` (and their `*_async` forms for async code), `await interact(user_id, text,
  dialogue_id="default", locale=None, response_expected=True, history=None)`; errors are
  `DialogueError`; `store` is a `dialogue.sessionstore.SessionStore`: `MemorySessions` (default) or
  `dialogue.sparqlsessions.SparqlSessions(endpoint)` (shared by processes on one SPARQL store);
- `dialogue.llm.spec.parse_spec("rules" | "ollama:gemma3:1b[@URL]" | "openai:MODEL[@URL]" |
  "openai-json:MODEL[@URL]" | "hybrid:<llm spec>") -> Backend(model, spec)`; errors are `SpecError`;
  `dialogue.llm.hybrid.HybridModel(inner)` is what a `hybrid:` spec builds; `await model.aclose()`
  when done with a model;
- `dialogue.evaluation.run(path, llm_spec) -> Report` (`score`, `claim_precision`) and `main(argv)`
  (the `situated eval` command).

Modules: intents (Intent.msg catalogue), schema (answer models, per-turn JSON schema), grounding
(KB snapshot), situation (snapshot as sentences), lexicon / resolution / clarify (referents), words /
commands / questions (the rules grammar), interpret + answers (the rules interpreter), validate (model
answer -> grounded intents), prompts, history, engine, sessions (+ sessionstore, sparqlsessions: where
dialogue state lives), evaluation, llm/ (backends).
"""
