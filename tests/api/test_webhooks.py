"""Outgoing webhooks against a real HTTP receiver started here: it fails, then recovers."""

from __future__ import annotations

import json
import logging
import threading
import time
from collections.abc import Iterator
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

import pytest

from api.courier import DeliveryConfig
from api.settings import IntentSettings
from api.webhooks import Webhook
from dialogue import intents as I
from dialogue.pushed.events import Pushed
from tests.api.conftest import Live, scene_settings
from tests.waiting import until


class Receiver:
    """An HTTP server that answers 500 while `failing`, holds requests while `hold` is clear, and
    keeps the JSON bodies it accepted, in order."""

    def __init__(self) -> None:
        self.failing = True
        self.hold = threading.Event()
        self.hold.set()
        self.accepted: list[dict[str, Any]] = []
        self.refused = 0
        receiver = self

        class Handler(BaseHTTPRequestHandler):
            def do_POST(self) -> None:
                body = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
                receiver.hold.wait(60)
                if receiver.failing:
                    receiver.refused += 1
                    self.send_response(500)
                else:
                    receiver.accepted.append(body)
                    self.send_response(204)
                self.end_headers()

            def log_message(self, *args: Any) -> None:
                return

        self.server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}/hook"
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()

    def close(self) -> None:
        self.hold.set()
        self.server.shutdown()
        self.server.server_close()


@pytest.fixture
def receiver() -> Iterator[Receiver]:
    receiver = Receiver()
    yield receiver
    receiver.close()


def hooked(live_factory: Any, receiver: Receiver, **values: Any) -> Live:
    intents = IntentSettings(webhooks=[receiver.url], webhook_backoff=0.05, webhook_max_backoff=0.2,
                             webhook_retries=100, **values)
    live: Live = live_factory(scene_settings(intents=intents))
    return live


def say(live: Live, text: str) -> dict[str, Any]:
    response = live.client.post("/dialogues/default/interactions", json={"user_id": "person_alice", "input": text})
    assert response.status_code == 200, response.text
    body: dict[str, Any] = response.json()
    return body


def health(live: Live) -> dict[str, Any]:
    body: dict[str, Any] = live.client.get("/health").json()
    return body


def test_deliveries_are_retried_until_the_receiver_recovers_and_health_says_so(
        live_factory: Any, receiver: Receiver) -> None:
    live = hooked(live_factory, receiver)
    n = live.services.bus.first - 1
    turn = say(live, "please bring me the cup")
    until(lambda: receiver.refused >= 2)
    status = health(live)
    assert status["status"] == "degraded"
    hook = status["components"]["webhook_0"]
    assert not hook["ok"] and hook["code"] == "webhook_failing" and "HTTP 500" in hook["reason"]
    assert any("webhook_0" in reason for reason in status["reasons"])
    receiver.failing = False
    until(lambda: len(receiver.accepted) == 1)
    assert receiver.accepted[0]["intent"] == turn["intents"][0] and receiver.accepted[0]["seq"] == n + 1
    until(lambda: health(live)["status"] == "ok")
    say(live, "hello")
    until(lambda: len(receiver.accepted) == 2)
    assert [body["seq"] for body in receiver.accepted] == [n + 1, n + 2]  # in order, each once


def test_a_turn_never_waits_for_a_webhook(live_factory: Any, receiver: Receiver) -> None:
    receiver.failing = False
    receiver.hold.clear()  # the receiver takes the request and does not answer
    live = hooked(live_factory, receiver, webhook_timeout=60)
    n = live.services.bus.first - 1
    assert say(live, "hello")["intents"][0]["intent"] == "__intent_greet__"
    assert say(live, "bring me the cup")["intents"]  # answered while the first delivery still hangs
    assert receiver.accepted == []
    receiver.hold.set()
    until(lambda: [b["seq"] for b in receiver.accepted] == [n + 1, n + 2])


def test_an_intent_with_json_values_is_delivered_as_pushed(live_factory: Any, receiver: Receiver) -> None:
    receiver.failing = False
    live = hooked(live_factory, receiver)
    intent = {"intent": "__intent_start_activity__", "source": "person_alice",
              "data": {"object": "quiz", "other_data": {"round": 3, "topics": ["art", "maths"], "hints": False}}}
    assert live.client.post("/intents", json={"intent": intent}).status_code == 200
    until(lambda: len(receiver.accepted) == 1)
    assert receiver.accepted[0]["intent"]["data"] == intent["data"]


def pushed(seq: int) -> Pushed:
    intent = I.make_intent(I.GREET, {"recipient": "p"}, source=I.ROBOT_ITSELF, confidence=1.0)
    return Pushed(seq, 0.0, "initiative", intent)


def test_a_full_queue_drops_its_oldest_event_and_counts_it() -> None:
    hook = Webhook("http://127.0.0.1:9/never", DeliveryConfig(queue=2))  # not started: nothing is sent
    for seq in (1, 2, 3):
        hook.enqueue(pushed(seq))
    assert hook.counts.dropped == 1 and hook.queued == 2
    status = hook.status()
    assert status.ok and "1 dropped" in status.reason and "2 queued" in status.reason


def test_a_delivery_given_up_after_its_retries_is_counted(receiver: Receiver) -> None:
    hook = Webhook(receiver.url, DeliveryConfig(retries=2, backoff=0.01, queue=10))
    hook.start()
    try:
        hook.enqueue(pushed(1))
        until(lambda: hook.counts.failed == 1)
        assert receiver.refused == 3  # the first attempt and two retries
        receiver.failing = False
        hook.enqueue(pushed(2))
        until(lambda: hook.counts.delivered == 1)
        status = hook.status()
        assert [b["seq"] for b in receiver.accepted] == [2] and status.ok
        # Recovered, but an intent was lost: /health still says how many.
        assert "1 delivered, 1 given up" in status.reason
    finally:
        hook.stop()


# --- a slow receiver and secrets in URLs (issue 26, item 11) -------------------------------------

class Trickler:
    """A receiver on loopback that answers one byte every half second, for a minute: each read
    comes well within any per-read timeout, the whole answer never does."""

    def __init__(self) -> None:
        self.requests = 0
        self.stop = threading.Event()
        outer = self

        class Handler(BaseHTTPRequestHandler):
            def do_POST(self) -> None:
                self.rfile.read(int(self.headers["Content-Length"]))
                outer.requests += 1
                for byte in b"HTTP/1.1 204 No Content\r\n\r\n" + b" " * 100:
                    if outer.stop.wait(0.5):
                        return
                    try:
                        self.wfile.write(bytes([byte]))
                        self.wfile.flush()
                    except OSError:
                        return

            def log_message(self, *args: Any) -> None:
                return

        self.server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}/hook"
        threading.Thread(target=self.server.serve_forever, daemon=True).start()

    def close(self) -> None:
        self.stop.set()
        self.server.shutdown()
        self.server.server_close()


def test_a_trickling_receiver_is_given_up_on_time_and_reported_slow(live_factory: Any) -> None:
    trickler = Trickler()
    try:
        intents = IntentSettings(webhooks=[trickler.url], webhook_timeout=2.0, webhook_retries=0)
        live: Live = live_factory(scene_settings(intents=intents))
        hook = live.services.webhooks.hooks[0]
        started = time.monotonic()
        say(live, "hello")
        until(lambda: hook.counts.failed == 1, timeout=30)
        took = time.monotonic() - started
        assert took < 2.0 + 3, f"one delivery held the webhook {took:.1f} s; its timeout is 2 s"
        status = health(live)
        assert status["status"] == "degraded"
        reported = status["components"]["webhook_0"]
        assert not reported["ok"] and "slow receiver" in reported["reason"], reported
    finally:
        trickler.close()


def test_webhook_and_model_urls_show_no_secrets(live_factory: Any, receiver: Receiver,
                                                caplog: pytest.LogCaptureFixture) -> None:
    receiver.failing = False
    secret_hook = receiver.url.replace("http://", "http://robot:pa55word@") + "?token=s3cr3t&room=4"
    intents = IntentSettings(webhooks=[secret_hook], webhook_retries=0)
    caplog.set_level(logging.INFO)
    live: Live = live_factory(scene_settings(intents=intents, llm="hybrid:openai:tiny@http://127.0.0.1:9/v1?key=k3y"))
    say(live, "hello")
    until(lambda: len(receiver.accepted) == 1)  # delivered, with its credentials
    receiver.failing = True
    say(live, "please bring me the cup")
    until(lambda: live.services.webhooks.hooks[0].counts.failed == 1)
    anonymous = live.client.get("/health").json()
    shown = json.dumps(anonymous) + caplog.text
    assert "webhook_0" in json.dumps(anonymous) and "openai:tiny" in json.dumps(anonymous)
    for secret in ("pa55word", "s3cr3t", "k3y"):
        assert secret not in shown, secret
    assert "[redacted]" in json.dumps(anonymous) and "room=4" in json.dumps(anonymous)


def test_secrets_in_a_webhooks_path_or_parameters_and_the_models_key_are_never_shown(
        live_factory: Any, receiver: Receiver, caplog: pytest.LogCaptureFixture) -> None:
    """Red team round 3 rerun: a Slack-style path secret, `auth_token=`, `client_secret=`,
    `x-api-key=` and `access-token=` were in anonymous /health and the log of every delivery, and
    the model URL's `key=` in the log, the turn's error and its trace (an anonymous read)."""
    receiver.failing = True
    secret_hook = (receiver.url + "/services/T000/B000/PATHSECRET?auth_token=s1&client_secret=s2&x-api-key=s3"
                   "&access-token=s4&room=4")
    intents = IntentSettings(webhooks=[secret_hook], webhook_retries=0)
    caplog.set_level(logging.INFO)
    live: Live = live_factory(scene_settings(intents=intents,
                                             llm="hybrid:openai:tiny@http://127.0.0.1:9/v1?key=k3y&api_key=k4y"))
    turn = say(live, "blorp the zingy wibble please")
    assert turn["error_msg"], "the model server is unreachable: the turn says why"
    until(lambda: live.services.webhooks.hooks[0].counts.failed >= 1)
    anonymous = json.dumps(live.client.get("/health").json())
    traces = live.client.get("/dialogues/default/turns").text
    shown = anonymous + caplog.text + json.dumps(turn) + traces
    assert "webhook_0" in anonymous and "room=4" in anonymous and "127.0.0.1:9/v1" in traces
    for secret in ("PATHSECRET", "s1", "s2", "s3", "s4", "k3y", "k4y"):
        assert f"{secret}&" not in shown and f"{secret}\"" not in shown and f"/{secret}" not in shown, secret
        assert f"={secret}" not in shown, secret
