"""Questions about the situation, on whole words."""

import pytest

from dialogue.understanding.parsed import Parse
from dialogue.understanding.questions import grammar
from dialogue.understanding.speech import plain
from kb import KB
from tests.dialogue.conftest import english, scene_kb
from tests.dialogue.understanding.test_interpret import say


def question(words: list[str]) -> Parse | None:
    return grammar.question(english(), words)


def expanded(text: str) -> list[str]:
    return plain.expanded(english(), text)


@pytest.mark.parametrize(
    ("text", "thing"),
    [
        ("how many mugs have we got", ("mugs",)),
        ("how many mugs do we have", ("mugs",)),
        ("how many green mugs have you got left", ("green", "mugs")),
        ("how many chairs are there in the hall", ("chairs", "in", "the", "hall")),
        ("how many mugs can you see", ("mugs",)),
        ("how many mugs are there", ("mugs",)),
        ("how many mugs", ("mugs",)),
    ],
)
def test_how_many_counts_the_words_before_the_questions_own_clause(text: str, thing: tuple[str, ...]) -> None:
    asked = question(text.split())
    assert asked is not None and asked.question == "how_many" and asked.slots == {"thing": thing}


def test_how_many_have_we_got_is_answered(office: KB) -> None:
    assert say(office, "how many mugs have we got").reply == (
        "I see two mugs: the green mug and the yellow mug.")  # fmt: skip


@pytest.mark.parametrize(
    ("text", "place", "relation"),
    [
        ("what is next to the window", ("the", "window"), ("next", "to")),
        ("whats by the door", ("the", "door"), ("by",)),
        ("what's behind the sofa", ("the", "sofa"), ("behind",)),
    ],
)
def test_what_is_near_a_thing_asks_about_its_relations(
    text: str, place: tuple[str, ...], relation: tuple[str, ...]
) -> None:
    asked = question(expanded(text))
    assert asked is not None and asked.question == "what_near"
    assert asked.slots == {"place": place, "relation": relation}


def test_is_someone_about_asks_whether_they_are_there() -> None:
    asked = question(["is", "maria", "about"])
    assert asked is not None and (asked.question, asked.slots) == ("can_see", {"thing": ("maria",)})


def test_a_name_with_front_is_a_place_and_at_home_is_here(office: KB) -> None:
    assert question(expanded("whats on the front bench")).question == "what_on"
    assert question(expanded("what is in front of you")).question == "what_see"
    assert question(expanded("who is home")).question == "who_see"
    assert "Carol" in say(office, "who is at home right now?").reply


def test_where_has_a_thing_gone_said_with_is(office: KB) -> None:
    p = question(expanded("wheres my mug gone"))
    assert p is not None and (p.question, p.slots["thing"]) == ("where", ("my", "mug"))
    assert "desk" in say(office, "er wheres the green mug gone").reply


@pytest.mark.parametrize(
    ("text", "thing"),
    [
        ("where did we put the stapler", ("the", "stapler")),
        ("where's the remote got to now", ("the", "remote")),
        ("where'd I leave my umbrella", ("my", "umbrella")),
        ("where would I find a pear", ("a", "pear")),
        ("please where I can find the laptop", ("the", "laptop")),
        ("any idea where Carol left her notebook", ("her", "notebook")),
        ("do you happen to know where the stapler went", ("the", "stapler")),
        ("has anyone seen the umbrella", ("the", "umbrella")),
        ("which room is the umbrella in", ("the", "umbrella")),
    ],
)
def test_where_questions_said_otherwise_ask_where_the_thing_is(text: str, thing: tuple[str, ...]) -> None:
    words = expanded(text)
    words = words[1:] if words[0] == "please" else words
    p = question(words)
    assert p is not None and (p.question, p.slots["thing"]) == ("where", thing)


def test_where_questions_said_otherwise_are_answered(office: KB) -> None:
    assert "hallway" in say(office, "Has anyone seen the umbrella?").reply
    assert "desk" in say(office, "Where did we put the stapler?").reply
    assert "hallway" in say(office, "Which room is the umbrella in?").reply
    # A verb of putting with more than a name before it is no where-question of this form.
    assert question(expanded("where is the man who left the umbrella")) != Parse(
        "question", question="where", slots={"thing": ("the", "umbrella")}
    )


def test_where_is_it_with_nothing_spoken_of_is_not_answered(office: KB) -> None:
    out = say(office, "where did you put it")
    assert not out.understood and "it" not in out.reply.split()


@pytest.mark.parametrize(
    ("text", "place"),
    [
        ("who is waiting in the office", ("the", "office")),
        ("who's on the shop floor", ("the", "shop", "floor")),
        ("who is at the desk", ("the", "desk")),
        ("tell me the name of the person in the office", ("the", "office")),
        ("what's the name of the man in the hallway", ("the", "hallway")),
        # a pointing word or a particle before the place
        ("who's that in the kitchen", ("the", "kitchen")),
        ("who is over by the desk", ("the", "desk")),
    ],
)
def test_who_questions_about_a_place_ask_who_is_there(text: str, place: tuple[str, ...]) -> None:
    p = question(expanded(text))
    assert p is not None and (p.question, p.slots["place"]) == ("who_in", place)


def test_who_is_there_is_answered_with_names() -> None:
    kb = scene_kb("office", "person_dan isIn hallway")
    assert "Dan" in say(kb, "Tell me the name of the person in the hallway.").reply
    assert "Dan" in say(kb, "Who's waiting in the hallway?").reply
    kb.close()
    who = question(expanded("who is Carol"))  # a name, not a place
    assert who is not None and who.question == "what_is"


@pytest.mark.parametrize(
    ("text", "answered"),
    [
        ("who do you see", True),
        ("who else is here", True),
        ("who can you see right now", True),
        ("who else is waiting", True),
        ("who is here today", True),
        ("who else is down the office today", True),
        # a verb the seeing question has no place for: some other question, not answered as it
        ("who else lives here", False),
        ("who works here", False),
        ("who am i", False),
    ],
)
def test_a_who_question_is_who_is_seen_only_with_every_word_accounted(
    office: KB, text: str, answered: bool
) -> None:
    asked = question(text.split())
    assert asked is not None and asked.question == "who_see"
    out = say(office, text)
    assert out.understood is answered and (out.reply == "I see you and Carol.") is answered


def test_who_is_in_a_place_not_here_says_so(office: KB) -> None:
    out = say(office, "who is in the kitchen?")
    assert out.reply == "Sorry, I don't know where the kitchen is."
    assert say(office, "who's in today?").reply == "I see you and Carol."  # no place: who is there


def test_show_me_where_is_guiding_not_a_question() -> None:
    # "show me where the lounge is": taken there (the frame of "show"); told, or shown what, asked
    assert question(expanded("show me where the lounge is")) is None
    asked = question(expanded("tell me where the lounge is"))
    assert asked is not None and asked.question == "where"
    shown = question(expanded("show me what is on the table"))
    assert shown is not None and shown.question == "what_on"


def test_what_is_on_a_thing_said_with_that_or_asked_to_be_described(office: KB) -> None:
    for text in ("what's that on the desk", "describe what's on the desk"):
        asked = question(expanded(text))
        assert asked is not None and asked.question == "what_on", text
        assert "stapler" in say(office, text).reply


@pytest.mark.parametrize(
    ("text", "thing"),
    [
        # whether there is any, said of the household
        ("do we still have nachos", ("nachos",)),
        ("have we got any tape", ("any", "tape")),
        ("is there still any water", ("any", "water")),
        ("are there still biscuits", ("biscuits",)),
        # when, said after someone's being here or a thing's place
        ("is Yuki here yet", ("yuki",)),
        ("is my fleece still on the chair", ("my", "fleece", "on", "the", "chair")),
    ],
)
def test_questions_said_indirectly_ask_what_is_there(text: str, thing: tuple[str, ...]) -> None:
    p = question(expanded(text))
    assert p is not None and (p.question, p.slots["thing"]) == ("can_see", thing)


@pytest.mark.parametrize("text", ["do you have to go", "do we still have to wait"])
def test_having_to_do_something_is_no_question_of_what_is_there(text: str) -> None:
    p = question(expanded(text))
    assert p is None or p.question != "can_see"


@pytest.mark.parametrize(
    ("text", "kind"),
    [
        ("describe the objects lying on the bench", "what_on"),
        ("list the things on the shelf", "what_on"),
        ("describe the people in the foyer", "who_in"),
    ],
)
def test_describing_what_is_somewhere_asks_what_or_who_is_there(text: str, kind: str) -> None:
    p = question(expanded(text))
    assert p is not None and p.question == kind


def test_describing_a_thing_alone_is_no_question_of_what_is_there() -> None:
    p = question(expanded("describe the bench"))
    assert p is None or p.question not in {"what_on", "who_in"}


@pytest.mark.parametrize(
    ("text", "kind", "thing"),
    [
        # a verb of how a thing is placed, before where: the thing is there
        ("whose phone is lying on the counter", "whose", ("phone", "on", "the", "counter")),
        ("whose keys are sitting on the bar", "whose", ("keys", "on", "the", "bar")),
        # "count" said as a command asks how many, when a noun phrase follows it
        ("count the canoes you can see in the shed", "how_many", ("the", "canoes", "in", "the", "shed")),
        ("count how many mugs there are", "how_many", ("mugs",)),
    ],
)
def test_placed_and_counted_things_are_asked_about(text: str, kind: str, thing: tuple[str, ...]) -> None:
    asked = question(text.split())
    assert asked is not None and asked.question == kind and asked.slots == {"thing": thing}


def test_count_without_a_noun_phrase_asks_nothing() -> None:
    assert question(["count", "to", "ten"]) is None
    assert question(["count", "me", "in"]) is None


@pytest.mark.parametrize(
    ("text", "kind", "place"),
    [
        ("which oars are on the rack", ("oars",), ("the", "rack")),
        ("which fruit is on the long table", ("fruit",), ("the", "long", "table")),
        ("what cups are sitting on the shelf", ("cups",), ("the", "shelf")),
    ],
)
def test_which_things_of_a_kind_are_on_a_place(text: str, kind: tuple[str, ...], place: tuple[str, ...]) -> None:
    asked = question(text.split())
    assert asked is not None and asked.question == "which_on"
    assert asked.slots["thing"] == kind and asked.slots["place"] == place


def test_what_is_on_a_place_is_not_of_a_kind() -> None:
    asked = question(["what", "is", "lying", "on", "the", "table"])
    assert asked is not None and asked.question == "what_on"


@pytest.mark.parametrize("text", ["who is down on the slipway", "who is out on the jetty", "who's up in the loft"])
def test_who_is_down_somewhere_asks_who_is_there(text: str) -> None:
    asked = question(expanded(text))
    assert asked is not None and asked.question == "who_in"
