"""Invalid Unicode is refused at the edge, route by route (issue 19, item 7): a lone surrogate (a JSON
escape, or UTF-8 bytes encoding one) or bytes that are not UTF-8, in a JSON body, a path, a query
string, a form, a SPARQL body, an uploaded document, the scene, the Rasa facade or a dialogue turn,
is a 400 naming the problem; nothing changes, and every route keeps answering."""

from __future__ import annotations

import json
from typing import Any

import pytest
from websockets.exceptions import InvalidStatus
from websockets.sync.client import connect

from tests.api.conftest import Live

JSON = {"content-type": "application/json"}
ENCODED = "%ED%A0%80"  # UTF-8 bytes of U+D800: not valid UTF-8
RAW = b"\xed\xa0\x80"
# (method, URL, headers, body) of every route that takes text, each with invalid Unicode in one place.
CASES: dict[str, tuple[str, str, dict[str, str], str | bytes | None]] = {
    "query POST": ("POST", "/kb/query", JSON, '{"patterns": ["?s rdfs:label \\"\\ud800\\""]}'),
    "query POST, low": ("POST", "/kb/query", JSON, '{"patterns": ["?s ?p ?o"], "vars": ["?s\\udc00"]}'),
    "query POST, raw bytes": ("POST", "/kb/query", JSON, b'{"patterns": ["?s ?p \\"' + RAW + b'\\""]}'),
    "query GET": ("GET", f"/kb/query?pattern={ENCODED}", {}, None),
    "revise": ("POST", "/kb/revise", JSON, '{"method": "add", "statements": ["cup_9 rdfs:label \\"\\ud800\\""]}'),
    "revise, N3 escape": ("POST", "/kb/revise", JSON,
                          '{"method": "add", "statements": ["cup_9 rdfs:label \\"\\\\ud800\\""]}'),
    "revise, models": ("POST", "/kb/revise", JSON, '{"method": "add", "statements": ["a b c"], "models": ["\\ud800"]}'),
    "apply": ("POST", "/kb/apply", JSON, '{"add": ["cup_9 rdfs:label \\"x\\ud800\\""]}'),
    "details": ("GET", f"/kb/details/cup{ENCODED}", {}, None),
    "details, models": ("GET", f"/kb/details/cup_1?models={ENCODED}", {}, None),
    "label": ("GET", f"/kb/label/{ENCODED}", {}, None),
    "lookup": ("GET", f"/kb/lookup?q=cup{ENCODED}", {}, None),
    "about": ("GET", f"/kb/about/{ENCODED}", {}, None),
    "classesof": ("GET", f"/kb/classesof/{ENCODED}", {}, None),
    "load turtle, raw bytes": ("POST", "/kb/load", {"content-type": "text/turtle"},
                               b'<http://x.org/a> <http://x.org/b> "' + RAW + b'" .'),
    "load turtle, escape": ("POST", "/kb/load", {"content-type": "text/turtle"},
                            '<http://x.org/a> <http://x.org/b> "\\ud800" .'),
    "load json-ld, escape": ("POST", "/kb/load", {"content-type": "application/ld+json"},
                             '{"@id": "http://x.org/a", "http://x.org/b": "\\ud800"}'),
    "load rdf/xml, char ref": ("POST", "/kb/load", {"content-type": "application/rdf+xml"},
                               '<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" '
                               'xmlns:o="http://x.org/"><rdf:Description rdf:about="http://x.org/a">'
                               '<o:b>&#xD800;</o:b></rdf:Description></rdf:RDF>'),
    "export": ("GET", f"/kb/export?model={ENCODED}", {}, None),
    "clear": ("POST", "/kb/clear", JSON, '{"keep_defaults": true, "x": "\\ud800"}'),
    "sparql GET": ("GET", f"/sparql?query=SELECT%20*%20WHERE%20%7B%3Fs%20%3Fp%20%22{ENCODED}%22%7D", {}, None),
    "sparql GET, escape": ("GET", "/sparql?query=SELECT%20%3Fx%20WHERE%20%7BBIND(%22%5Cud800%22%20AS%20%3Fx)%7D",
                           {}, None),
    "sparql POST query": ("POST", "/sparql", {"content-type": "application/sparql-query"},
                          b'SELECT ?x WHERE { BIND("' + RAW + b'" AS ?x) }'),
    "sparql POST query, escape": ("POST", "/sparql", {"content-type": "application/sparql-query"},
                                  'SELECT ?x WHERE { BIND("\\ud800" AS ?x) }'),
    "sparql POST form": ("POST", "/sparql", {"content-type": "application/x-www-form-urlencoded"},
                         f"query=SELECT%20*%20WHERE%20%7B%3Fs%20%3Fp%20%22{ENCODED}%22%7D"),
    "events": ("GET", f"/kb/events?pattern={ENCODED}", {}, None),
    "start dialogue": ("POST", "/dialogues", JSON, '{"role": {"name": "\\ud800"}}'),
    "interaction": ("POST", "/dialogues/default/interactions", JSON,
                    '{"user_id": "person_alice", "input": "\\ud800 bring me the cup"}'),
    "interaction, user": ("POST", "/dialogues/default/interactions", JSON,
                          '{"user_id": "person\\udfff", "input": "hello"}'),
    "interaction, history": ("POST", "/dialogues/default/interactions", JSON,
                             '{"user_id": "p", "input": "hi", "history": [{"speaker": "p", "text": "\\ud83d"}]}'),
    "interaction, path": ("POST", f"/dialogues/{ENCODED}/interactions", JSON, '{"user_id": "p", "input": "hi"}'),
    "end dialogue": ("DELETE", f"/dialogues/{ENCODED}", {}, None),
    "webhook": ("POST", "/webhooks/rest/webhook", JSON, '{"sender": "person_alice", "message": "\\ud800"}'),
    "webhook, token": ("POST", f"/webhooks/rest/webhook?token={ENCODED}", JSON, '{"sender": "p", "message": "hi"}'),
    "parse": ("POST", "/model/parse", JSON, '{"text": "\\udc00 cup"}'),
    "put scene": ("PUT", "/scene", JSON, '{"entities": [{"id": "box_1", "label": "\\ud800", "x": 1, "y": 0}]}'),
    "put scene svg": ("PUT", "/scene", {"content-type": "image/svg+xml"},
                      '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><text>&#xDC00;</text></svg>'),
    "put entity": ("PUT", "/scene/entities/box_1", JSON, '{"label": "red \\ud800", "x": 1, "y": 0}'),
    "put entity, id": ("PUT", f"/scene/entities/box{ENCODED}", JSON, '{"x": 1, "y": 0}'),
    "delete entity": ("DELETE", f"/scene/entities/box{ENCODED}", {}, None),
}


def _state(live: Live) -> tuple[Any, ...]:
    scene = live.client.get("/scene")
    assert scene.status_code == 200, scene.text
    return live.services.kb.revision, live.services.kb.export("nt"), scene.json()["entities"], live.services.dialogues.ids()


@pytest.fixture
def scened(live: Live) -> Live:
    assert live.client.put("/scene/entities/cup_7", json={"label": "red cup", "x": 1.0, "y": 0.2}).status_code == 200
    return live


@pytest.mark.parametrize("case", list(CASES), ids=list(CASES))
def test_invalid_unicode_is_a_clear_400_and_changes_nothing(scened: Live, case: str) -> None:
    method, url, headers, body = CASES[case]
    before = _state(scened)
    response = scened.client.request(method, url, headers=headers, content=body)
    assert response.status_code == 400, response.text
    error = response.json()
    assert set(error) == {"status", "code", "message", "details"} and error["status"] == 400
    assert any(word in error["message"] for word in ("not valid Unicode", "not valid UTF-8", "not well-formed",
                                                     "reference to invalid character")), error
    assert _state(scened) == before
    # The red team's follow-up requests, which answered 500 once such text got in.
    assert scened.client.post("/kb/query", json={"patterns": ["?s ?p ?o"]}).status_code == 200
    assert scened.client.get("/kb/details/cup_7").status_code == 200
    assert scened.client.get("/sparql", params={"query": "SELECT * WHERE { ?s ?p ?o } LIMIT 5"}).status_code == 200
    assert scened.client.post("/webhooks/rest/webhook", json={"sender": "p", "message": "hi"}).status_code == 200
    turn = {"user_id": "person_alice", "input": "what do you see?"}
    assert scened.client.post("/dialogues/default/interactions", json=turn).status_code == 200


def test_the_edge_names_the_problem(live: Live) -> None:
    lone = live.client.post("/model/parse", headers=JSON, content='{"text": "\\udc00 cup"}').json()
    assert lone["code"] == "invalid_unicode" and "\\udc00 at character 10 is a lone surrogate" in lone["message"]
    raw = live.client.get(f"/kb/lookup?q=a{ENCODED}").json()
    assert raw["code"] == "invalid_unicode" and raw["message"].startswith("the query string is not valid UTF-8")


def test_valid_escapes_and_pairs_pass_the_edge(live: Live) -> None:
    body = {"method": "add", "statements": ['cup_9 rdfs:label "tea \U0001F375 \\\\ud800 é"']}
    text = json.dumps(body)  # ASCII: the emoji as a surrogate pair, the backslash escaped
    assert "\\ud83c\\udf75" in text and live.client.post("/kb/revise", headers=JSON, content=text).status_code == 200
    rows = live.client.get("/kb/query", params={"pattern": "cup_9 rdfs:label ?l"}).json()
    assert rows == [{"l": "tea \U0001F375 \\ud800 é"}]  # a backslash and 'ud800': text, not an escape
    assert live.client.get("/kb/lookup", params={"q": "tea \U0001F375"}).status_code == 200


def test_a_websocket_with_invalid_unicode_in_its_url_is_refused(live: Live) -> None:
    with pytest.raises(InvalidStatus), connect(f"{live.ws_url}/kb/events/ws?x={ENCODED}", open_timeout=10):
        pass
    # In a message: a JSON escape is refused by the message's JSON parser, an N3 escape by the KB.
    for message, expected in (('{"patterns": ["?s rdfs:label \\"\\ud800\\""]}', "hex escape"),
                              ('{"patterns": ["?s rdfs:label \\"\\\\ud800\\""]}', "not valid Unicode")):
        with connect(f"{live.ws_url}/kb/events/ws", open_timeout=10) as ws:
            ws.send(message)
            reply = json.loads(ws.recv(timeout=10))
            assert 400 <= reply["status"] < 500 and expected in reply["message"], reply
