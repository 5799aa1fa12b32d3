"""The web viewer in headless Chromium against the real service: graph, query, facts, live updates,
chat. Selectors are the page's own ids and data attributes (see api/viewer/index.html)."""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from typing import Any

from playwright.sync_api import expect

from tests.e2e.conftest import Opener, Service


def node(page: Any, term: str) -> Any:
    return page.locator(f'.node[data-id="{term}"]')


def edge(page: Any, s: str, p: str, o: str) -> Any:
    return page.locator(f'.edge[data-s="{s}"][data-p="{p}"][data-o="{o}"]')


def fact_rows(page: Any) -> list[list[str]]:
    rows = page.locator("#facts tbody tr").all()
    return [[cell.inner_text().strip() for cell in row.locator("td").all()[:3]] for row in rows]


def results(page: Any) -> tuple[list[str], list[list[str]]]:
    head = [th.inner_text() for th in page.locator("#results thead th").all()]
    body = [[td.inner_text() for td in tr.locator("td").all()] for tr in page.locator("#results tbody tr").all()]
    return head, body


def test_page_starts_from_myself_with_labels_and_classes(service: Service, open_viewer: Opener) -> None:
    page, watch = open_viewer(service)
    for term in ("cup_1", "table_1", "person_alice"):
        node(page, term).wait_for()
    # Labels come from label.default; categories from the concept's classes.
    expect(node(page, "person_alice").locator(".node-label")).to_have_text("Alice")
    for term, category in [("person_alice", "person"), ("myself", "robot"), ("table_1", "furniture"),
                           ("cup_1", "object"), ("Robot", "class")]:
        expect(node(page, term)).to_have_class(re.compile(rf"\bcat-{category}\b"))
    edge(page, "myself", "sees", "cup_1").wait_for()
    edge(page, "myself", "isA", "Robot").wait_for()
    # Neighbours shown together are linked even before anyone expands them.
    edge(page, "cup_1", "isOn", "table_1").wait_for()
    expect(page.locator("#concept-label")).to_have_text("myself")
    expect(page.locator("#facts tbody tr", has_text="cup_1")).to_have_count(1)
    assert ["myself", "sees", "cup_1"] in fact_rows(page)
    assert watch.errors == []


def test_clicking_a_node_expands_it_and_shows_its_facts(service: Service, open_viewer: Opener) -> None:
    page, _ = open_viewer(service)
    assert node(page, "kitchen").count() == 0
    node(page, "table_1").click()
    node(page, "kitchen").wait_for()
    edge(page, "table_1", "isIn", "kitchen").wait_for()
    expect(page.locator("#concept-label")).to_have_text("table_1")
    expect(page.locator("#facts tbody tr", has_text="kitchen").first).to_be_visible()
    assert ["table_1", "isIn", "kitchen"] in fact_rows(page)
    expect(node(page, "table_1")).to_have_class(re.compile(r"\bexpanded\b"))


def test_query_runs_a_conjunction_with_ctrl_enter(service: Service, open_viewer: Opener) -> None:
    page, _ = open_viewer(service)
    page.fill("#patterns", "?h sees ?o\n?o rdf:type dbr:Cup")
    page.press("#patterns", "Control+Enter")
    page.wait_for_selector('#query-status[data-kind="ok"]')
    assert results(page) == (["?h", "?o"], [["myself", "cup_1"]])
    assert page.locator("#query-status").inner_text() == "1 row"

    page.fill("#patterns", "?x sees")
    page.press("#patterns", "Control+Enter")
    page.wait_for_selector('#query-status[data-kind="error"]')
    assert "sees" in page.locator("#query-status").inner_text()


def test_facts_added_elsewhere_and_here_appear_live_and_removals_too(service: Service,
                                                                      open_viewer: Opener) -> None:
    page, _ = open_viewer(service)
    # Another client writes: the event stream brings it without a reload.
    service.revise(["person_bob rdf:type Human", "person_bob rdfs:label \"Bob\"", "myself sees person_bob"])
    node(page, "person_bob").wait_for()
    expect(node(page, "person_bob")).to_have_class(re.compile(r"\bcat-person\b"))
    expect(node(page, "person_bob").locator(".node-label")).to_have_text("Bob")
    edge(page, "myself", "sees", "person_bob").wait_for()
    expect(page.locator("#facts tbody tr", has_text="person_bob")).to_have_count(1)

    # The page's own form, here without a token since the service has none.
    page.fill("#statements", "myself sees plant_1\nplant_1 rdf:type dbr:Plant")
    page.select_option("#method", "add")
    page.click("#revise button[type=submit]")
    page.wait_for_selector('#revise-status[data-kind="ok"]')
    node(page, "plant_1").wait_for()
    expect(page.locator("#facts tbody tr", has_text="plant_1")).to_have_count(1)
    assert ["myself", "sees", "plant_1"] in fact_rows(page)

    # Retract from the table's row action, then a removal made elsewhere (from the commit feed).
    page.locator("#facts tbody tr", has_text="plant_1").get_by_role("button", name="retract…").click()
    assert page.input_value("#statements") == "myself sees plant_1"
    assert page.input_value("#method") == "retract"
    page.click("#revise button[type=submit]")
    node(page, "plant_1").wait_for(state="detached")
    expect(page.locator("#facts tbody tr", has_text="plant_1")).to_have_count(0)
    service.revise(["myself sees person_bob"], "retract")
    edge(page, "myself", "sees", "person_bob").wait_for(state="detached")
    expect(page.locator("#facts tbody tr", has_text="person_bob")).to_have_count(0)


def test_a_change_whose_refresh_fails_is_read_again_and_drawn(service: Service, open_viewer: Opener) -> None:
    page, watch = open_viewer(service)
    node(page, "cup_1").wait_for()
    refused: list[str] = []

    def busy_once(route: Any) -> None:
        # The first read of each end of the new fact meets a busy service, as on a loaded machine.
        term = route.request.url.split("/kb/details/")[1].split("?")[0]
        if term not in refused:
            refused.append(term)
            route.fulfill(status=503, content_type="application/json",
                          body=json.dumps({"status": 503, "code": "busy", "message": "busy", "details": {}}))
        else:
            route.continue_()

    for term in ("cup_1", "person_alice"):
        page.route(f"**/kb/details/{term}?*", busy_once)
    service.revise(["cup_1 isNextTo person_alice"])
    edge(page, "cup_1", "isNextTo", "person_alice").wait_for()
    assert sorted(refused) == ["cup_1", "person_alice"]
    # The refused read is the one failure the page reported; nothing else went wrong.
    assert [e for e in watch.errors if "503" not in e] == []


def test_a_refused_read_is_not_tried_again(service: Service, open_viewer: Opener) -> None:
    page, _ = open_viewer(service)
    node(page, "cup_1").wait_for()
    asked: list[str] = []

    def refuse_cup(route: Any) -> None:  # a refusal stays one: no point asking again
        asked.append("cup_1")
        route.fulfill(status=403, content_type="application/json",
                      body=json.dumps({"status": 403, "code": "forbidden", "message": "no", "details": {}}))

    def busy_once(route: Any) -> None:
        asked.append("person_alice")
        if asked.count("person_alice") == 1:
            route.fulfill(status=503, content_type="application/json",
                          body=json.dumps({"status": 503, "code": "busy", "message": "busy", "details": {}}))
        else:
            route.continue_()

    page.route("**/kb/details/cup_1?*", refuse_cup)
    page.route("**/kb/details/person_alice?*", busy_once)
    service.revise(["cup_1 isNextTo person_alice"])
    # The retry reads the terms in the order the change named them: cup_1 would be asked before
    # person_alice's second read draws the edge.
    edge(page, "cup_1", "isNextTo", "person_alice").wait_for()
    assert asked == ["cup_1", "person_alice", "person_alice"]


def test_chat_shows_reply_and_intents(service: Service, open_viewer: Opener) -> None:
    page, _ = open_viewer(service)
    page.fill("#user-id", "person_alice")
    page.fill("#chat-input", "pick up the cup")
    page.press("#chat-input", "Enter")
    reply = page.locator(".msg.robot:not(.waiting)")
    reply.wait_for()
    assert page.locator(".msg.user p").inner_text() == "pick up the cup"
    assert "cup" in reply.locator(".reply").inner_text()
    assert "question" not in (reply.get_attribute("class") or "")
    intents = json.loads(reply.locator("pre.json").inner_text())
    assert [(i["intent"], i["data"], i["source"]) for i in intents] == [
        ("__intent_grab_object__", {"object": "cup_1"}, "person_alice")]
    assert page.input_value("#chat-input") == ""


def test_an_ambiguous_request_shows_a_clarification_question(service: Service, open_viewer: Opener) -> None:
    service.revise(["cup_2 rdf:type dbr:Cup", "cup_2 isOn table_1", "myself sees cup_2"])
    page, _ = open_viewer(service)
    page.fill("#chat-input", "grab the cup")
    page.press("#chat-input", "Enter")
    question = page.locator(".msg.robot.question")
    question.wait_for()
    text = question.locator(".reply").inner_text()
    assert text.endswith("?") and "cup_1" in text and "cup_2" in text
    assert question.locator(".who").inner_text() == "robot asks"


def test_writes_send_the_token_entered_in_the_page(start_service: Callable[..., Service],
                                                   open_viewer: Opener) -> None:
    service = start_service(token="s3cret")
    page, _ = open_viewer(service)
    page.fill("#statements", "myself sees lamp_1")
    page.click("#revise button[type=submit]")
    page.wait_for_selector('#revise-status[data-kind="error"]')
    assert "Authorization" in page.locator("#revise-status").inner_text()

    page.fill("#token", "s3cret")
    page.press("#token", "Enter")
    page.fill("#statements", "myself sees lamp_1")
    page.click("#revise button[type=submit]")
    page.wait_for_selector('#revise-status[data-kind="ok"]')
    node(page, "lamp_1").wait_for()
    assert page.evaluate("sessionStorage.getItem('situated.token')") == "s3cret"


def test_inferred_edges_are_drawn_apart_from_asserted_ones(service: Service, open_viewer: Opener) -> None:
    page, _ = open_viewer(service)
    asserted = edge(page, "cup_1", "isOn", "table_1")
    inferred = edge(page, "table_1", "placeOf", "cup_1")
    expect(inferred).to_have_attribute("data-kind", "inferred")
    expect(asserted).to_have_attribute("data-kind", "asserted")
    # The fact table marks them too, and the toggle hides the inferred edges only.
    node(page, "cup_1").click()
    expect(page.locator("#facts tbody tr.inferred", has_text="placeOf")).to_have_count(1)
    expect(page.locator("#facts tbody tr.asserted", has_text="isOn")).to_have_count(1)
    page.uncheck("#show-inferred")
    expect(inferred).to_be_hidden()
    expect(asserted).to_be_visible()


def test_the_query_box_starts_empty_with_an_example_as_placeholder(service: Service, open_viewer: Opener) -> None:
    page, _ = open_viewer(service)
    assert page.input_value("#patterns") == ""
    assert "?" in (page.get_attribute("#patterns", "placeholder") or "")
    page.click("#patterns")
    page.keyboard.type("myself sees ?o")
    assert page.input_value("#patterns") == "myself sees ?o"  # typed text is the query, nothing before it
    page.press("#patterns", "Control+Enter")
    page.wait_for_selector('#query-status[data-kind="ok"]')
    assert ["cup_1"] in results(page)[1]


def test_objects_get_the_icon_of_their_kind(service: Service, open_viewer: Opener) -> None:
    service.revise(["book_9 rdf:type dbr:Book", "myself sees book_9", "apple_9 rdf:type dbr:Apple",
                    "myself sees apple_9", "fork_9 rdf:type dbr:Fork", "myself sees fork_9",
                    "thing_9 rdf:type Artifact", "myself sees thing_9"])
    page, _ = open_viewer(service)
    icons = [("cup_1", "cup"), ("book_9", "book"), ("apple_9", "fruit"), ("fork_9", "utensil"),
             ("thing_9", "object"), ("table_1", "furniture"), ("person_alice", "person"), ("myself", "robot")]
    for term, icon in icons:
        expect(node(page, term).locator("use.node-icon")).to_have_attribute("href", f"#icon-{icon}")
    expect(node(page, "thing_9")).to_have_class(re.compile(r"\bcat-object\b"))
    # Every icon a node names is drawn, and the generic object is not one of the kinds.
    for _, icon in icons:
        assert page.locator(f"symbol#icon-{icon}").count() == 1, icon
    generic = page.locator("symbol#icon-object").inner_html()
    kinds = ["cup", "book", "fruit", "utensil", "bottle", "plant", "phone", "bin"]
    assert all(page.locator(f"symbol#icon-{kind}").inner_html() != generic for kind in kinds)
