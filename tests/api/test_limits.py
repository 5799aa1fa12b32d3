"""Request bounds give clear 413 errors (subscriber bounds: see test_events)."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

from api.settings import Limits, Settings
from tests.api.conftest import SCENE, Live


def _limited(live_factory) -> Live:  # type: ignore[no-untyped-def]
    limits = Limits(max_body_bytes=2048, max_statements=2, max_patterns=2)
    live: Live = live_factory(Settings(scene=SCENE, limits=limits))
    return live


def test_body_size_with_and_without_content_length(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = _limited(live_factory)
    big = json.dumps({"statements": ["a b c"] * 400, "method": "add"}).encode()
    declared = live.client.post("/kb/revise", content=big, headers={"content-type": "application/json"})
    assert declared.status_code == 413
    assert declared.json()["code"] == "body_too_large" and "2048" in declared.json()["message"]

    def chunks() -> Iterator[bytes]:
        for start in range(0, len(big), 512):
            yield big[start:start + 512]

    streamed = live.client.post("/kb/revise", content=chunks(), headers={"content-type": "application/json"})
    assert streamed.status_code == 413 and streamed.json()["code"] == "body_too_large"
    assert live.services.kb.find(["a b c"]) == []
    small = live.client.post("/kb/revise", json={"statements": ["a b c"], "method": "add"})
    assert small.status_code == 200


def test_statement_and_pattern_counts(live_factory) -> None:  # type: ignore[no-untyped-def]
    live = _limited(live_factory)
    many = live.client.post("/kb/revise", json={"statements": ["a b c", "a b d", "a b e"], "method": "add"})
    assert many.status_code == 413
    assert many.json() == {"status": 413, "code": "too_many_statements",
                           "message": "3 statements in one request; the limit is 2",
                           "details": {"count": 3, "limit": 2}}
    patterns = ["?a b ?c", "?c d ?e", "?e f ?g"]
    assert live.client.post("/kb/query", json={"patterns": patterns}).json()["code"] == "too_many_patterns"
    by_get = live.client.get("/kb/query", params=[("pattern", p) for p in patterns])
    assert by_get.status_code == 413
    assert live.client.get("/kb/events", params=[("pattern", p) for p in patterns]).status_code == 413


def test_query_rows_and_utterance_length_are_bounded(live_factory) -> None:  # type: ignore[no-untyped-def]
    from api.settings import Limits, Settings
    from tests.api.conftest import SCENE

    live = live_factory(Settings(scene=SCENE, limits=Limits(max_rows=3, max_input_chars=50)))
    many = live.client.post("/kb/query", json={"patterns": ["?s ?p ?o"]})
    assert many.status_code == 413 and many.json()["code"] == "too_many_rows"
    assert len(live.client.post("/kb/query", json={"patterns": ["myself sees ?o", "?o rdf:type dbr:Cup"]}).json()) == 1
    long = live.client.post("/dialogues/default/interactions", json={"user_id": "u", "input": "x" * 51})
    assert long.status_code == 413 and long.json()["code"] == "input_too_long"
    assert live.client.post("/webhooks/rest/webhook", json={"sender": "u", "message": "y" * 51}).status_code == 413


def test_models_per_request_are_bounded_and_a_refusal_creates_none(live_factory) -> None:  # type: ignore[no-untyped-def]
    """Issue 19, item 9: each new model copies the ontology's closure; 1,000 in one revise took 42 s
    and 2.5 GB. Every write or query naming more than the limit is a 413, and nothing is created."""
    live = live_factory(Settings(scene=SCENE, limits=Limits(max_models=3)))
    many = [f"m{i}" for i in range(4)]
    before = live.services.kb.models()
    for method, path, kwargs in [
        ("POST", "/kb/revise", {"json": {"statements": ["a b c"], "method": "add", "models": many}}),
        ("POST", "/kb/apply", {"json": {"add": ["a b c"], "models": many}}),
        ("POST", "/kb/load", {"params": {"models": many}, "content": "<http://x.org/a> <http://x.org/b> 1 .",
                              "headers": {"content-type": "text/turtle"}}),
        ("POST", "/kb/query", {"json": {"patterns": ["?s ?p ?o"], "models": many}}),
        ("GET", "/kb/query", {"params": {"pattern": "?s ?p ?o", "models": many}}),
    ]:
        response = live.client.request(method, path, **kwargs)
        assert response.status_code == 413, (path, response.text)
        assert response.json()["code"] == "too_many_models" and "the limit is 3" in response.json()["message"]
    assert live.services.kb.models() == before
    ok = live.client.post("/kb/revise", json={"statements": ["a b c"], "method": "add", "models": many[:3]})
    assert ok.status_code == 200 and set(many[:3]) <= set(live.services.kb.models())
    assert live.services.kb.find("a b c", models=["m2"]) == ["a b c"]


def test_the_models_of_the_kb_and_what_each_person_model_holds_are_bounded(live_factory) -> None:  # type: ignore[no-untyped-def]
    """16 new models a request once took memory from 178 MB to 1.96 GB over 100 requests, and 300 new
    speakers saying "I like tea" added 342 MB: each model costs a copy of the ontology's closure."""
    live = live_factory(Settings(scene=SCENE, limits=Limits(max_total_models=4, max_model_statements=10)))
    kb = live.services.kb

    def revise(statements: list[str], models: list[str]) -> Any:
        return live.client.post("/kb/revise", json={"statements": statements, "method": "add", "models": models})

    assert revise(["person_alice likes dbr:Tea"], ["person_alice", "person_tom"]).status_code == 200
    refused = revise(["x y z"], ["m1", "m2"])  # 5 models in all
    assert (refused.status_code, refused.json()["code"]) == (413, "model_limit")
    assert "the KB holds 3 models" in refused.json()["message"] and "limits.max_total_models" in refused.json()["message"]
    assert kb.models() == ["default", "person_alice", "person_tom"]
    # A new speaker's belief needs a model of its own: past the bound the turn says it could not remember.
    assert revise(["x y z"], ["m1"]).status_code == 200  # the fourth
    revision = kb.revision
    answer = live.client.post("/dialogues/default/interactions", json={"user_id": "person_new", "input": "I like tea"})
    assert answer.status_code == 200
    assert answer.json()["response"] == "Sorry, I could not remember that."
    assert "the limit is 4" in answer.json()["error_msg"]
    assert "person_new" not in kb.models() and not kb.exist(["person_new likes ?x"])  # neither model changed
    assert kb.revision == revision + 1  # only the new person joined the KB (as perception would say)
    # What one person's model holds: past it, refused, saying so (it holds Alice's liking already).
    big = revise([f"thing_{n} isOn table_1" for n in range(10)], ["person_tom"])
    assert (big.status_code, big.json()["code"]) == (413, "model_limit")
    assert "model 'person_tom' would hold 11 statements of its own; the limit is 10" in big.json()["message"]
    assert revise([f"thing_{n} isOn table_1" for n in range(9)], ["person_tom"]).status_code == 200
    said = live.client.post("/dialogues/default/interactions", json={"user_id": "person_tom", "input": "I like coffee"})
    assert said.json()["response"] == "Sorry, I could not remember that."  # the eleventh
    assert "would hold 11 statements" in said.json()["error_msg"]


def test_the_model_bounds_have_sensible_defaults() -> None:
    limits = Limits()
    assert (limits.max_total_models, limits.max_model_statements) == (256, 1000)
