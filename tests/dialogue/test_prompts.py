import string
from pathlib import Path

import pytest

from dialogue.history import ASSISTANT_USER_ID, SYSTEM_USER_ID, Utterance
from dialogue.llm.base import ChatMessage, TurnContext
from dialogue.prompts import PromptError, PromptSet, intent_list, load_template, render
from dialogue.reference.grounding import build_snapshot
from kb import KB

SNAPSHOTS = Path(__file__).parent / "snapshots"


def dump(messages: tuple[ChatMessage, ...]) -> str:
    return "".join(f"### {m.role}\n{m.content}\n" for m in messages)


def kitchen_context(kb: KB) -> TurnContext:
    history = (
        Utterance("person_alice", "hello"),
        Utterance(ASSISTANT_USER_ID, "Hello Alice!"),
        Utterance(SYSTEM_USER_ID, "Tom left the house."),
    )
    return TurnContext("bring me the cookbook", "person_alice", build_snapshot(kb), history, "en_GB", "Ari")


def test_rendered_prompt_matches_the_snapshot(kitchen: KB) -> None:
    rendered = dump(PromptSet.load().messages(kitchen_context(kitchen)))
    expected = (SNAPSHOTS / "kitchen_prompt.txt").read_text(encoding="utf-8")
    assert rendered == expected


def test_static_part_first_situation_last(kitchen: KB) -> None:
    prompts = PromptSet.load()
    messages = prompts.messages(kitchen_context(kitchen))
    assert messages[0].role == "system" and "Ari" in messages[0].content
    assert "[cup_1]" not in messages[0].content  # the situation never enters the cacheable prefix
    assert messages[-1].role == "user" and "[cup_1]" in messages[-1].content
    assert messages[-1].content.rstrip().endswith('They say: "bring me the cookbook"')
    # History roles (D14): assistant and system keep their roles, users are quoted with their id.
    assert [m.role for m in messages[1:4]] == ["user", "assistant", "system"]
    assert messages[1].content == 'person_alice "hello"'
    kitchen.update(["pear_1 rdf:type dbr:Pear", "myself sees pear_1"])
    again = prompts.messages(kitchen_context(kitchen))
    assert again[0] == messages[0] and "[pear_1]" in again[-1].content  # D12: re-rendered, not appended


def test_every_placeholder_is_substituted(kitchen: KB) -> None:
    for message in PromptSet.load().messages(kitchen_context(kitchen)):
        assert "$" not in message.content


def test_render_is_strict_both_ways() -> None:
    template = string.Template("Hello $name, I am $robot.")
    assert render(template, {"name": "Ann", "robot": "Ari"}) == "Hello Ann, I am Ari."
    with pytest.raises(PromptError, match="missing \\['robot'\\]"):
        render(template, {"name": "Ann"})
    with pytest.raises(PromptError, match="unused \\['extra'\\]"):
        render(template, {"name": "Ann", "robot": "Ari", "extra": "x"})
    with pytest.raises(PromptError, match="no prompt template"):
        load_template("nope")


def test_intent_list_names_constants_and_keys() -> None:
    text = intent_list()
    assert "- grab_object: object\n" in text
    assert "- say: input, recipient?\n" in text
    assert "- place_object: recipient, object?\n" in text
    assert text.endswith("- suspend") and "raw_user_input" not in text


def test_repair_message_says_what_was_wrong() -> None:
    message = PromptSet.load().repair_message("object 'evil_1' is not an id")
    assert message.role == "user" and "object 'evil_1' is not an id" in message.content


def test_the_system_prompt_explains_compound_commands(kitchen: KB) -> None:
    system = PromptSet.load().messages(kitchen_context(kitchen))[0].content
    assert "Several actions" in system and '"user_intent" is their\n  list' in system and "order" in system
