"""The verb-frame table: verbs as lemmas, multi-word verbs, roles found by their prepositions in any
order, particles, adjuncts, and a row being all it takes to add a verb."""

import shutil
from collections.abc import Iterator
from importlib import resources
from pathlib import Path

import pytest

from dialogue import intents as I
from dialogue.understanding.language import Language
from dialogue.understanding.parsed import Parse
from dialogue.understanding.requests import commands
from kb import KB
from tests.dialogue import conftest
from tests.dialogue.conftest import english
from tests.dialogue.understanding.test_interpret import say


def parse(text: str, robot_name: str = "") -> Parse:
    """The grammar's reading of the words (in English)."""
    return commands.parse(english(), text, robot_name)


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        ("took the vase", I.GRAB_OBJECT, {"object": ("the", "vase")}),
        ("grabbing the vase", I.GRAB_OBJECT, {"object": ("the", "vase")}),
        ("puts the vase on the piano", I.PLACE_OBJECT, {"object": ("the", "vase"), "recipient": ("the", "piano")}),
        ("brought the vase to Ann", I.BRING_OBJECT, {"object": ("the", "vase"), "recipient": ("ann",)}),
        ("would you mind fetching the vase for Ann", I.BRING_OBJECT,
         {"object": ("the", "vase"), "recipient": ("ann",)}),
    ],
)  # fmt: skip
def test_verbs_are_read_as_lemmas(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.act, p.intent) == ("command", intent)
    assert {k: p.slots[k] for k in slots} == slots


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        ("nip down to the garage", I.MOVE_TO, {"goal": ("the", "garage")}),
        ("head over to the garage", I.MOVE_TO, {"goal": ("the", "garage")}),
        ("find your way to the garage", I.MOVE_TO, {"goal": ("the", "garage")}),
        ("take hold of the vase", I.GRAB_OBJECT, {"object": ("the", "vase")}),
        ("pick the vase up from the piano", I.GRAB_OBJECT, {"object": ("the", "vase", "from", "the", "piano")}),
        ("shake hands with Ann", I.PERFORM_MOTION, {"recipient": ("ann",)}),
        ("speak with Ann", I.ENGAGE_WITH, {"recipient": ("ann",)}),
    ],
)  # fmt: skip
def test_multi_word_verbs_and_particles(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.act, p.intent) == ("command", intent)
    assert {k: p.slots[k] for k in slots} == slots


def test_a_particle_inside_a_phrase_is_part_of_it() -> None:
    assert parse("pick up the back cushion").slots["object"] == ("the", "back", "cushion")
    assert parse("bring the down pillow over to Ann").slots == {"object": ("the", "down", "pillow"),
                                                                "recipient": ("ann",)}  # fmt: skip


def test_roles_are_found_by_their_prepositions_in_any_order() -> None:
    before, after = parse("hand the vase to Ann"), parse("hand to Ann the vase")
    assert before.slots == after.slots == {"object": ("the", "vase"), "recipient": ("ann",)}
    assert parse("carry over to the garage the blue vase").slots == {
        "object": ("the", "blue", "vase"), "recipient": ("the", "garage")}  # fmt: skip


@pytest.mark.parametrize(
    ("text", "intent", "slots", "adjunct"),
    [
        ("go to the garage through the side door", I.MOVE_TO, {"goal": ("the", "garage")},
         ("through", "the", "side", "door")),
        ("go through the side door to the garage", I.MOVE_TO, {"goal": ("the", "garage")},
         ("through", "the", "side", "door")),
        ("move to the garage by crossing the yard", I.MOVE_TO, {"goal": ("the", "garage")},
         ("by", "crossing", "the", "yard")),
        ("greet Ann on my behalf", I.GREET, {"recipient": ("ann",)}, ("on", "my", "behalf")),
        ("take the vase to Ann when you can", I.BRING_OBJECT, {"object": ("the", "vase"), "recipient": ("ann",)},
         ("when", "you", "can")),
        ("put the vase on the piano carefully", I.PLACE_OBJECT,
         {"object": ("the", "vase"), "recipient": ("the", "piano")}, ("carefully",)),
        ("go along the hall to the garage", I.MOVE_TO, {"goal": ("the", "garage")}, ("along", "the", "hall")),
        ("grab the ladder before someone trips on it", I.GRAB_OBJECT, {"object": ("the", "ladder")},
         ("before", "someone", "trips", "on", "it")),
    ],
)  # fmt: skip
def test_adjuncts_are_not_part_of_a_referent(
    text: str, intent: str, slots: dict[str, tuple[str, ...]], adjunct: tuple[str, ...]
) -> None:
    p = parse(text)
    assert (p.intent, p.slots) == (intent, slots)
    assert adjunct in p.adjuncts


def test_a_preposition_of_the_frame_is_a_role_not_an_adjunct() -> None:
    # "for me" is an adjunct of greeting but the recipient of bringing.
    assert parse("say hi to Ann for me").slots == {"recipient": ("ann",)}
    assert parse("fetch the vase for me").slots == {"object": ("the", "vase"), "recipient": ("me",)}
    # "through" with nothing after it is a particle: "walk me through to the garage".
    p = parse("walk me through to the garage")
    assert (p.intent, p.slots) == (I.GUIDE, {"recipient": ("me",), "goal": ("the", "garage")})


def test_pointing_fills_the_place_and_is_dropped_when_the_place_is_named() -> None:
    assert parse("put the vase right here").slots == {"object": ("the", "vase"), "recipient": ("me",)}
    p = parse("show me the way to the garage")
    assert (p.intent, p.slots) == (I.GUIDE, {"recipient": ("me",), "goal": ("the", "garage")})


def test_a_default_role_is_marked_implicit() -> None:
    p = parse("lead the way")
    assert (p.intent, p.slots["goal"], p.implicit) == (I.GUIDE, ("there",), frozenset({"recipient"}))
    assert parse("lead Ann to the garage").implicit == frozenset()


def test_a_past_form_never_makes_a_request_or_a_vocative_of_a_statement() -> None:
    # "took" alone may be a misheard request, but "someone left..." is a statement about someone.
    assert parse("someone left the keys on the piano").act == "unknown"
    assert parse("Ann took the vase").act == "unknown"


def test_a_place_is_said_back_with_its_preposition(office: KB) -> None:
    assert say(office, "put the pear next to the laptop").reply == "OK, I will put the pear next to the laptop."
    assert say(office, "put the pear under the desk").reply == "OK, I will put the pear under the desk."
    assert say(office, "put the pear on the desk").reply == "OK, I will put the pear on the desk."


#: One more frame of frames.toml, as a language folder says it.
EXTRA_ROW = f"""
[[frame]]
verbs = "ferry|cart"
intent = "{I.BRING_OBJECT}"
direct = "object"
slots = {{ recipient = "to|over to" }}
"""


@pytest.fixture
def extra_row(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Iterator[None]:
    """English with one more frame, read from a copy of its folder (the session's English is left as
    it is)."""
    folder = tmp_path / "en"
    shutil.copytree(Path(str(resources.files("dialogue.understanding") / "lang" / "en")), folder)
    with (folder / "frames.toml").open("a") as frames_file:
        frames_file.write(EXTRA_ROW)
    extended = Language.read(folder)
    monkeypatch.setattr(conftest, "english", lambda: extended)
    yield


def test_a_row_is_all_it_takes_to_add_a_verb(extra_row: None, office: KB) -> None:
    out = say(office, "Ari could you be ferrying the stapler over to Carol")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_carol"})
    # Its inflections, compound requests and vocatives come with it.
    steps = say(office, "carol cart the pear to Dan and then go to the hallway").steps()
    assert [(o.intent, o.roles) for o in steps] == [
        (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_dan"}),
        (I.MOVE_TO, {"goal": "hallway"}),
    ]


def test_without_the_row_the_verb_is_not_understood(office: KB) -> None:
    assert say(office, "ferry the stapler over to Carol").intent is None


@pytest.mark.parametrize(
    ("text", "act", "intent", "slots"),
    [
        ("get over to the garage", "command", I.MOVE_TO, {"goal": ("the", "garage")}),
        ("run to the garage", "command", I.MOVE_TO, {"goal": ("the", "garage")}),
        ("run the dishwasher", "command", I.START_ACTIVITY, {}),
        ("swing by the piano", "command", I.MOVE_TO, {"goal": ("the", "piano")}),
        ("release the vase", "command", I.PLACE_OBJECT, {"object": ("the", "vase")}),
        ("leave the vase by the door", "command", I.PLACE_OBJECT, {"object": ("the", "vase"),
                                                                   "recipient": ("the", "door")}),
        ("carry the vase into the garage", "command", I.BRING_OBJECT, {"object": ("the", "vase"),
                                                                       "recipient": ("the", "garage")}),
        ("ask Ann to close the gate", "command", I.SAY, {"recipient": ("ann",)}),
        ("ask Ann if she wants tea", "command", I.SAY, {"recipient": ("ann",)}),  # "do you want tea?"
        ("bring me something to drink", "command", I.BRING_OBJECT, {"object": ("something", "to", "drink"),
                                                                    "recipient": ("me",)}),
        ("would you be able to pick up the vase", "command", I.GRAB_OBJECT, {"object": ("the", "vase")}),
        ("gimme the vase would ya", "command", I.BRING_OBJECT, {"object": ("the", "vase"), "recipient": ("me",)}),
        ("hand Ann the vase asap", "command", I.BRING_OBJECT, {}),
    ],
)  # fmt: skip
def test_more_verbs_and_phrasings(
    text: str, act: str, intent: str | None, slots: dict[str, tuple[str, ...]]
) -> None:
    p = parse(text)
    assert (p.act, p.intent) == (act, intent)
    assert {k: p.slots[k] for k in slots} == slots
    if text.startswith("ask Ann to"):
        assert p.text == "please close the gate"
    if text.endswith("asap"):
        assert p.slots == {"rest": ("ann", "the", "vase")} and p.adjuncts == (("asap",),)


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        ("Ann would like the vase", I.BRING_OBJECT, {"object": ("the", "vase"), "recipient": ("ann",)}),
        ("my aunt needs her shawl", I.BRING_OBJECT, {"object": ("her", "shawl"), "recipient": ("my", "aunt")}),
        ("she could use the vase", I.BRING_OBJECT, {"object": ("the", "vase"), "recipient": ("her",)}),
        ("give Ann a hand getting to the garage", I.GUIDE, {"recipient": ("ann",), "goal": ("the", "garage")}),
        ("wheel the trolley over to the piano", I.BRING_OBJECT, {"object": ("the", "trolley"),
                                                                 "recipient": ("the", "piano")}),
    ],
)  # fmt: skip
def test_someone_elses_wish_and_a_helping_hand(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.intent, {k: p.slots[k] for k in slots}) == (intent, slots)


@pytest.mark.parametrize("text", ["the kettle needs descaling", "it needs a new battery", "Ann needs to rest"])
def test_a_thing_needing_something_is_no_request(text: str) -> None:
    assert parse(text).intent is None


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        ("chuck the rag in the sink", I.PLACE_OBJECT, {"object": ("the", "rag"), "recipient": ("the", "sink")}),
        ("toss the peel into the compost", I.PLACE_OBJECT, {"object": ("the", "peel"),
                                                            "recipient": ("the", "compost")}),
        ("throw the wrapper in the bin", I.PLACE_OBJECT, {"object": ("the", "wrapper"), "recipient": ("the", "bin")}),
        # "out" is a particle of carrying, "out of" says where from
        ("take grandad out to the garden", I.BRING_OBJECT, {"object": ("grandad",), "recipient": ("the", "garden")}),
        ("get me a lemon out of the bowl", I.BRING_OBJECT, {"object": ("a", "lemon", "from", "the", "bowl")}),
        # the way is no one's name, with or without its article
        ("show Noor way to the exit", I.GUIDE, {"recipient": ("noor",), "goal": ("the", "exit")}),
        ("show Noor the way to the exit", I.GUIDE, {"recipient": ("noor",), "goal": ("the", "exit")}),
        # where a thing goes is where to put it
        ("the butter goes back in the fridge", I.PLACE_OBJECT, {"object": ("the", "butter"),
                                                               "recipient": ("the", "fridge")}),
        ("these belong on the top shelf", I.PLACE_OBJECT, {"object": ("these",), "recipient": ("the", "top", "shelf")}),
        ("the plates should go in the rack", I.PLACE_OBJECT, {"object": ("the", "plates"),
                                                             "recipient": ("the", "rack")}),
        # "take me": the place just spoken of (the interpreter finds it), else it asks where
        ("can you take me", I.GUIDE, {"recipient": ("me",), "goal": ("there",)}),
        # a request replacing an earlier one, a tag naming the listener: neither is a referent
        ("give it to Noor instead", I.BRING_OBJECT, {"object": ("it",), "recipient": ("noor",)}),
        ("pick up the ladder mate", I.GRAB_OBJECT, {"object": ("the", "ladder")}),
        # being somewhere is going there ("wait for me" is no place: not this row)
        ("go and wait in the lobby", I.MOVE_TO, {"goal": ("the", "lobby")}),
        ("stay by the gate", I.MOVE_TO, {"goal": ("the", "gate")}),
        # throwing to someone is bringing
        ("chuck me the towel", I.BRING_OBJECT, {"object": ("the", "towel"), "recipient": ("me",)}),
        ("toss the keys to Noor", I.BRING_OBJECT, {"object": ("the", "keys"), "recipient": ("noor",)}),
        ("show Noor where the exit is", I.GUIDE, {"recipient": ("noor",), "goal": ("the", "exit")}),
        ("the kettle lives on the counter", I.PLACE_OBJECT, {"object": ("the", "kettle"),
                                                             "recipient": ("the", "counter")}),
        # pointing after "me" says where the thing is, not where it goes
        ("fetch me that ladder over there", I.BRING_OBJECT, {"recipient": ("me",)}),
        ("reach the landing", I.MOVE_TO, {"goal": ("the", "landing")}),
        ("come back", I.MOVE_TO, {"goal": ("me",)}),
    ],
)  # fmt: skip
def test_verbs_and_phrasings_of_everyday_speech(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.act, p.intent) == ("command", intent)
    assert {k: p.slots[k] for k in slots} == slots


@pytest.mark.parametrize("text", ["the bus goes to town", "I go in the morning", "where does the salt go"])
def test_where_something_goes_is_no_request_without_a_place_to_put_it(text: str) -> None:
    assert parse(text).intent != I.PLACE_OBJECT


@pytest.mark.parametrize(
    ("text", "slots"),
    [
        ("get Noor her scarf", {"rest": ("noor", "her", "scarf")}),
        ("take him the kettle", {"rest": ("him", "the", "kettle")}),
        ("take all the plates", {"object": ("all", "the", "plates")}),  # a quantifier is nobody
        ("get the kettle", {"object": ("the", "kettle")}),
    ],
)
def test_getting_or_taking_someone_something_is_bringing_it(text: str, slots: dict[str, tuple[str, ...]]) -> None:
    assert parse(text).slots == slots


@pytest.mark.parametrize("text", ["wait for me", "stay"])
def test_waiting_with_no_place_is_no_motion(text: str) -> None:
    assert parse(text).intent in {None, I.STOP_ACTIVITY}


def test_wait_there_is_at_the_place_spoken_of_and_wait_here_is_no_place() -> None:
    p = parse("wait for me there")
    assert (p.intent, p.slots) == (I.MOVE_TO, {"goal": ("there",)})
    assert parse("stay over there").slots == {"goal": ("there",)}
    assert parse("wait here").intent == parse("stay put").intent == I.STOP_ACTIVITY  # staying put
    assert parse("wait").act == "unknown"  # ("wait, ...": an interjection)
    # waiting for someone is staying where it is, whoever for
    for said in ("wait for me", "wait for Oskar", "please wait for Ana"):
        assert parse(said).intent == I.STOP_ACTIVITY, said


def test_following_someone_is_an_activity_whom_to_follow_its_recipient() -> None:
    p = parse("follow me")
    assert (p.intent, p.text, p.slots) == (I.START_ACTIVITY, "follow", {"recipient": ("me",)})
    p = parse("follow Oskar")
    assert (p.intent, p.text, p.slots) == (I.START_ACTIVITY, "follow", {"recipient": ("oskar",)})
    assert parse("follow").intent is None  # whom is not said


def test_staying_with_someone_is_engaging_with_them() -> None:
    assert parse("stay with Alice").slots == {"recipient": ("alice",)}
    assert parse("stay with me").intent == I.ENGAGE_WITH


def test_say_hello_alone_greets_someone_the_interpreter_finds() -> None:
    p = parse("say hello")
    assert (p.intent, p.slots, p.implicit) == (I.GREET, {"recipient": ("me",)}, frozenset({"recipient"}))
    assert parse("say hello to Ann").slots == {"recipient": ("ann",)}
    assert parse("say hello world").intent == I.SAY  # words to say, not a greeting of no one


@pytest.mark.parametrize("text", ["say good morning to Lars", "say g'day to Raj", "Say good evening to Ann"])
def test_a_greeting_said_to_someone_greets_them(text: str) -> None:
    p = parse(text)
    assert (p.intent, set(p.slots)) == (I.GREET, {"recipient"})
    assert parse("say good night to Raj").intent == I.SAY  # a parting, said as words


def test_what_the_waiting_is_for_is_an_adjunct() -> None:
    p = parse("wait there for the delivery van")
    assert (p.intent, p.slots, p.adjuncts) == (I.MOVE_TO, {"goal": ("there",)}, (("for", "the", "delivery", "van"),))
    assert parse("wait for me").slots == {"awaited": ("me",)}  # no place


def test_an_activity_is_kicked_off_and_whom_it_is_for_is_not_its_name() -> None:
    p = parse("kick off story time for the little ones")
    assert (p.intent, p.text) == (I.START_ACTIVITY, "story_time")


@pytest.mark.parametrize("text", ["now do the same with the blue one", "do that again", "start it"])
def test_an_activity_said_only_by_what_was_done_before_is_none(office: KB, text: str) -> None:
    out = say(office, text)
    assert out.intent is None and out.more == ()


def test_carrying_the_speaker_is_no_request_of_the_robots() -> None:
    assert parse("can you carry me to my room").intent is None
    assert parse("lift me up").intent is None
    assert parse("carry me the box").intent == I.BRING_OBJECT  # whom for, then what
    assert parse("carry the box to the hall").intent == I.BRING_OBJECT


@pytest.mark.parametrize("text", ["pop the stapler over here, would you", "chuck the stapler over here", "bung the stapler here"])
def test_a_thing_popped_over_here_is_brought_to_the_speaker(office: KB, text: str) -> None:
    out = say(office, text)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "stapler_1", "recipient": "person_bob"})


def test_a_thing_popped_on_a_place_or_over_there_is_put_there(office: KB) -> None:
    out = say(office, "pop the stapler on the shelf")
    assert (out.intent, out.roles) == (I.PLACE_OBJECT, {"object": "stapler_1", "recipient": "shelf_9"})
    there = say(office, "pop the stapler over there", history=[("user", "what is on the shelf?")])
    assert there.intent != I.BRING_OBJECT
    assert say(office, "pop the stapler somewhere safe").intent is None  # where is asked


@pytest.mark.parametrize("text", ["introduce yourself to Carol", "Introduce yourself to Carol, please"])
def test_introducing_itself_to_someone_greets_them(office: KB, text: str) -> None:
    out = say(office, text)
    assert (out.intent, out.roles) == (I.GREET, {"recipient": "person_carol"})
