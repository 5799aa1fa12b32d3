"""The ROS client of knowledge_core's API against situated's node, over a real graph: the README's
example, and what it answers where knowledge_core's own client has defects. The client runs in a
subprocess under ROS (the test process never imports rclpy)."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import textwrap
from typing import Any

from tests.api.ros.conftest import ROOT, RosNode

#: Blocks of the README and the guides that run under ROS against a node (`python` blocks run in tests/test_docs.py).
ROS_BLOCK = re.compile(r"```python ros\n(.*?)```", re.S)


def run_under_ros(code: str, env: dict[str, str], timeout: float = 120) -> tuple[Any, str]:
    """Run ``code`` in a ROS process; it prints one JSON value last: that value, and the output."""
    done = subprocess.run([sys.executable, "-c", code], env={**env, "PYTHONPATH": f"{ROOT}:{env['PYTHONPATH']}"},
                          capture_output=True, text=True, timeout=timeout, check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1]), done.stdout + done.stderr


def test_the_ros_guide_example_runs_against_the_node(ros_node: RosNode, ros_env: dict[str, str]) -> None:
    blocks = [b for page in (ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")))
              for b in ROS_BLOCK.findall(page.read_text())]
    assert blocks, "the ROS guide has an example"
    code = textwrap.dedent(f"""
        import doctest, json, os
        blocks = {blocks!r}
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
        for number, block in enumerate(blocks, 1):
            runner.run(doctest.DocTestParser().get_doctest(block, {{}}, f"README ROS block {{number}}", "README.md", 0))
        print(json.dumps(runner.failures))
        os._exit(0)  # the client's executor thread need not wind down
    """)
    failures, output = run_under_ros(code, ros_env)
    assert failures == 0, output


def test_the_client_answers_as_documented(ros_node: RosNode, ros_env: dict[str, str]) -> None:
    code = textwrap.dedent("""
        import json, os, time
        from api.ros.client.kb import KB, KbError
        kb = KB(timeout=30)
        out = {}
        kb.add(["johnny rdf:type Human", 'johnny rdfs:label "A que Johnny"', 'johnny rdfs:label "Jojo"@fr'])
        out["labels"] = [kb.label("johnny"), kb.label("johnny", "fr"), kb.label("johnny", "de")]
        kb.add(["nono isNice true"], ["model1"])
        out["exist"] = [kb.exist(["nono isNice true"], ["model1"]), kb.exist(["nono isNice true"])]  # K7
        out["quoted"] = kb['johnny rdfs:label "A que Johnny"']  # K2: the quotes are kept
        try:
            kb.add(["toto"])
        except KbError as exc:
            out["refused"] = exc.value
        try:
            kb.subscribe(["toto"], print)
        except KbError as exc:
            out["refused_event"] = exc.value
        seen = []
        event = kb.subscribe(["?h rdf:type Human"], seen.append)
        kb += ["ari rdf:type Human"]
        for _ in range(400):
            if seen:
                break
            time.sleep(0.025)
        out["seen"] = seen
        out["unsubscribed"] = [kb.unsubscribe(event), kb.unsubscribe(event)]
        kb.close()
        print(json.dumps(out))
        os._exit(0)
    """)
    out, _ = run_under_ros(code, ros_env)
    assert out["labels"] == ["A que Johnny", "Jojo", "A que Johnny"]
    assert out["exist"] == [True, False]
    assert out["quoted"] == ['johnny rdfs:label "A que Johnny"']
    assert "'toto'" in out["refused"] and "3 terms" in out["refused"]
    assert "refused the subscription to ['toto']" in out["refused_event"]
    assert out["seen"] == [[{"h": "ari"}]]
    assert out["unsubscribed"] == [True, False]
    assert "/kb/events refused ['toto']" in ros_node.server.log.read_text()


def test_without_a_kb_node_the_client_says_so_in_time(ros_env: dict[str, str]) -> None:
    code = textwrap.dedent("""
        import json, os, time
        from api.ros.client.kb import KB, KbError
        started = time.monotonic()
        try:
            KB(timeout=1.0)
        except KbError as exc:
            print(json.dumps([exc.value, time.monotonic() - started]))
        os._exit(0)
    """)
    (message, took), _ = run_under_ros(code, ros_env)
    assert "/kb/manage is not available (waited 1 s)" in message and took < 30
