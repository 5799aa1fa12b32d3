"""What the ROS client makes of patterns and of ``kb[...]`` keys, before any ROS call."""

from __future__ import annotations

from typing import Any

import pytest

from api.ros.client.patterns import Find, Lookup, anonymous, item, named_variables
from kb import KB, KbError


def test_each_star_becomes_an_anonymous_variable_of_its_own_across_the_call() -> None:
    assert anonymous(["* likes *", "?x isIn *", "a b c"]) == ["?__1 likes ?__2", "?x isIn ?__3", "a b c"]


def test_quoted_literals_keep_their_quotes_and_spaces() -> None:
    # knowledge_core's client splits with shlex and loses the quotes (kb-compat K2).
    assert anonymous(['* rdfs:label "A que * Johnny"@fr']) == ['?__1 rdfs:label "A que * Johnny"@fr']


def test_anonymous_patterns_read_as_knowledge_core_reads_stars() -> None:
    kb = KB()
    kb += ["alfred likes icecream", "alfred rdf:type Human"]
    for patterns in (["* likes *"], ["?who likes *"], ["* * *"]):
        assert kb.find(anonymous(patterns), named_variables(patterns) or None) == kb.find(patterns)


def test_named_variables_in_order_once() -> None:
    assert named_variables(["?a likes ?b", "?b isIn *", "?__c sees ?a"]) == ["?a", "?b"]


@pytest.mark.parametrize(
    ("key", "asked"),
    [
        ("* rdf:type Robot", Find(["* rdf:type Robot"], [])),
        (("s p o", ["model1"]), Find(["s p o"], ["model1"])),
        (("?a desires ?x", "?x rdf:type Action"), Find(["?a desires ?x", "?x rdf:type Action"], [])),
        (("?a desires ?x", "?x rdf:type Action", ["m"]), Find(["?a desires ?x", "?x rdf:type Action"], ["m"])),
        ('johnny rdfs:label "A que Johnny"', Find(['johnny rdfs:label "A que Johnny"'], [])),
        ("alfred", Lookup("alfred", [])),
        ("alfred likes", Lookup("alfred likes", [])),
        (("ville rose", ["m"]), Lookup("ville rose", ["m"])),
    ],
)
def test_keys_read_as_knowledge_cores_client_reads_them(key: Any, asked: Find | Lookup) -> None:
    assert item(key) == asked


@pytest.mark.parametrize("key", [42, (), ("a b c", 3)])
def test_other_keys_are_refused(key: Any) -> None:
    with pytest.raises(KbError, match="kb"):
        item(key)
