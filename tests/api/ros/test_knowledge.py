"""knowledge_core's ROS services on the service's KB: success, json and error_msg as knowledge_core
answers them; a refused write changes nothing."""

from __future__ import annotations

import json

from api.settings import Settings
from tests.api.ros.conftest import Probe, RosNode

QUERY = "kb_msgs/srv/Query"
REVISE = "kb_msgs/srv/Revise"
MANAGE = "kb_msgs/srv/Manage"
ABOUT = "kb_msgs/srv/About"


def test_revise_then_query_then_retract(ros_node: RosNode, probe: Probe) -> None:
    added = probe.call("/kb/revise", REVISE, method="update", statements=["mug_1 isOn shelf_1", "mug_1 rdf:type dbr:Cup"])
    assert added == {"success": True, "error_msg": ""}
    found = probe.call("/kb/query", QUERY, patterns=["?m isOn shelf_1", "?m rdf:type dbr:Cup"], vars=["?m"])
    assert found["success"] is True and json.loads(found["json"]) == [{"m": "mug_1"}]
    anonymous = probe.call("/kb/query", QUERY, patterns=["?__a isOn shelf_1", "?__a rdf:type ?__c"])  # knowledge_core's '*'
    assert {"var1": "mug_1", "var2": "dbr:Cup"} in json.loads(anonymous["json"])
    assert probe.call("/kb/revise", REVISE, method="retract", statements=["mug_1 isOn shelf_1"])["success"] is True
    assert json.loads(probe.call("/kb/query", QUERY, patterns=["?m isOn shelf_1"])["json"]) == []


def test_a_malformed_statement_is_refused_whole_with_a_clear_error(ros_node: RosNode, probe: Probe) -> None:
    before = ros_node.http.get("/health").json()
    refused = probe.call("/kb/revise", REVISE, method="update", statements=["cat_1 isOn mat_1", "toto"])
    assert refused["success"] is False
    assert "'toto'" in refused["error_msg"] and "3 terms" in refused["error_msg"]
    assert json.loads(probe.call("/kb/query", QUERY, patterns=["cat_1 isOn ?x"])["json"]) == []
    assert ros_node.http.get("/health").json()["kb"]["revision"] == before["kb"]["revision"]


def test_an_unknown_manage_action_and_method_say_what_is_wrong(ros_node: RosNode, probe: Probe) -> None:
    manage = probe.call("/kb/manage", MANAGE, action="explode")
    assert manage["success"] is False and "'explode'" in manage["error_msg"] and "clear" in manage["error_msg"]
    revise = probe.call("/kb/revise", REVISE, method="frobnicate", statements=["a likes b"])
    assert revise["success"] is False and "frobnicate" in revise["error_msg"]


def test_more_patterns_than_the_limit_are_refused_as_over_rest(ros_node: RosNode, probe: Probe) -> None:
    limit = Settings().limits.max_patterns
    refused = probe.call("/kb/query", QUERY, patterns=[f"?x likes thing_{n}" for n in range(limit + 1)])
    assert refused["success"] is False and "limit" in refused["error_msg"]


def test_about_lookup_and_details(ros_node: RosNode, probe: Probe) -> None:
    probe.call("/kb/revise", REVISE, method="update", statements=['book_1 rdfs:label "cookbook"', "book_1 isOn shelf_1"])
    about = probe.call("/kb/about", ABOUT, term="book_1")
    assert ["book_1", "isOn", "shelf_1"] in json.loads(about["json"])
    lookup = probe.call("/kb/lookup", "kb_msgs/srv/Lookup", query="cookbook")
    assert ["book_1", "instance"] in json.loads(lookup["json"])
    details = json.loads(probe.call("/kb/details", ABOUT, term="book_1")["json"])
    assert details["id"] == "book_1" and details["label"]["default"] == "cookbook"
    probe.call("/kb/revise", REVISE, method="update", statements=['book_1 rdfs:label "livre de cuisine"@fr'])
    # What knowledge_core's client reads from /kb/label: the labels by language.
    assert json.loads(probe.call("/kb/label", ABOUT, term="book_1")["json"]) == {
        "default": "cookbook", "fr": "livre de cuisine"}


def test_facts_topics_add_and_remove(ros_node: RosNode, probe: Probe) -> None:
    probe("publish", topic="/kb/add_fact", type="std_msgs/msg/String", message={"data": "lamp_1 isOn desk_1"})
    for _ in range(200):
        if json.loads(probe.call("/kb/query", QUERY, patterns=["lamp_1 isOn ?d"])["json"]):
            break
    assert json.loads(probe.call("/kb/query", QUERY, patterns=["lamp_1 isOn ?d"])["json"]) == [{"d": "desk_1"}]


def test_manage_clear_empties_the_kb_as_kb_msgs_documents_unless_keep_defaults(ros_node: RosNode, probe: Probe) -> None:
    ontology = ["?c rdfs:subClassOf Agent"]
    assert json.loads(probe.call("/kb/query", QUERY, patterns=ontology)["json"])
    probe.call("/kb/revise", REVISE, method="update", statements=["ari rdf:type Robot"])
    kept = probe.call("/kb/manage", MANAGE, action="clear", parameters=["keep_defaults"])
    assert kept["success"] is True
    assert json.loads(probe.call("/kb/query", QUERY, patterns=["ari ?p ?o"])["json"]) == []
    assert json.loads(probe.call("/kb/query", QUERY, patterns=ontology)["json"])  # the ontology stayed
    assert probe.call("/kb/manage", MANAGE, action="clear")["success"] is True
    assert json.loads(probe.call("/kb/query", QUERY, patterns=ontology)["json"]) == []  # everything went


def test_a_clear_with_an_unknown_parameter_changes_nothing(ros_node: RosNode, probe: Probe) -> None:
    before = ros_node.http.get("/health").json()["kb"]["revision"]
    refused = probe.call("/kb/manage", MANAGE, action="clear", parameters=["keep_default"])
    assert refused["success"] is False and "'keep_default'" in refused["error_msg"]
    assert "keep_defaults" in refused["error_msg"]
    assert ros_node.http.get("/health").json()["kb"]["revision"] == before


def test_a_request_carrying_more_text_than_a_rest_body_may_is_refused(ros_node: RosNode, probe: Probe) -> None:
    limit = Settings().limits.max_body_bytes
    huge = "cat_1 says " + '"' + "m" * limit + '"'
    refused = probe.call("/kb/revise", REVISE, method="update", statements=[huge])
    assert refused["success"] is False and "characters of text; the limit is" in refused["error_msg"]
    assert json.loads(probe.call("/kb/query", QUERY, patterns=["cat_1 says ?x"])["json"]) == []
    lookup = probe.call("/kb/lookup", "kb_msgs/srv/Lookup", query="x" * (limit + 1))
    assert lookup["success"] is False and "limit" in lookup["error_msg"]
