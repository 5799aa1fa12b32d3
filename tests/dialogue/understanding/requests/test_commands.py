import pytest

from dialogue import intents as I
from dialogue.understanding.parsed import Parse
from dialogue.understanding.requests import commands
from kb import KB
from tests.dialogue.conftest import english
from tests.dialogue.understanding.test_interpret import say


def parse(text: str, robot_name: str = "") -> Parse:
    """The grammar's reading of the words (in English)."""
    return commands.parse(english(), text, robot_name)


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        ("Pick up the cup", I.GRAB_OBJECT, {"object": ("the", "cup")}),
        ("pick the mug up, please", I.GRAB_OBJECT, {"object": ("the", "mug")}),
        ("hand me the towel", I.BRING_OBJECT, {"object": ("the", "towel"), "recipient": ("me",)}),
        ("get the towel for me", I.BRING_OBJECT, {"object": ("the", "towel"), "recipient": ("me",)}),
        ("carry the box over to Ann", I.BRING_OBJECT, {"object": ("the", "box"), "recipient": ("ann",)}),
        (
            "set the vase on top of the piano",
            I.PLACE_OBJECT,
            {"object": ("the", "vase"), "recipient": ("the", "piano")},
        ),
        (
            "move the vase to the piano",
            I.PLACE_OBJECT,
            {"object": ("the", "vase"), "recipient": ("the", "piano")},
        ),
        ("head over to the garage", I.MOVE_TO, {"goal": ("the", "garage")}),
        ("come here", I.MOVE_TO, {"goal": ("me",)}),
        ("walk me to the exit", I.GUIDE, {"recipient": ("me",), "goal": ("the", "exit")}),
        ("lead the way to the lobby", I.GUIDE, {"recipient": ("me",), "goal": ("the", "lobby")}),
        ("engage with Ann", I.ENGAGE_WITH, {"recipient": ("ann",)}),
        ("would you mind picking up the vase", I.GRAB_OBJECT, {"object": ("the", "vase")}),
        ("do you mind putting the vase on the piano", I.PLACE_OBJECT,
         {"object": ("the", "vase"), "recipient": ("the", "piano")}),
        ("please get hold of the vase", I.GRAB_OBJECT, {"object": ("the", "vase")}),
        ("make your way to the garage", I.MOVE_TO, {"goal": ("the", "garage")}),
        ("go down to the cellar", I.MOVE_TO, {"goal": ("the", "cellar")}),
        ("go and stand by the piano", I.MOVE_TO, {"goal": ("the", "piano")}),
        ("could you welcome Ann", I.GREET, {"recipient": ("ann",)}),
        ("fetch me the vase, would you?", I.BRING_OBJECT, {"object": ("the", "vase"), "recipient": ("me",)}),
        ("um great bring it to me", I.BRING_OBJECT, {"object": ("it",), "recipient": ("me",)}),
    ],
)  # fmt: skip
def test_command_frames(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.act, p.intent) == ("command", intent)
    for key, value in slots.items():
        assert p.slots[key] == value


@pytest.mark.parametrize(
    ("text", "intent", "free"),
    [
        ('please say "see you later, alligator" to Ann', I.SAY, "see you later, alligator"),
        ("tell Ann dinner is served", I.SAY, "dinner is served"),
        ("tell Ann to come downstairs", I.SAY, "please come downstairs"),
        ("start the memory game", I.START_ACTIVITY, "memory_game"),
        ("water the plants", I.START_ACTIVITY, "water_plants"),
        ("stop vacuuming", I.STOP_ACTIVITY, "vacuuming"),
        ("that's enough", I.STOP_ACTIVITY, None),
        ("dance for me", I.PERFORM_MOTION, "dance"),
        ("wake up", I.WAKEUP, None),
        ("time to go to sleep", I.SUSPEND, None),
    ],
)
def test_free_form_values(text: str, intent: str, free: str | None) -> None:
    p = parse(text)
    assert (p.act, p.intent, p.text) == ("command", intent, free)


def test_quoted_text_is_kept_verbatim_even_with_to_inside() -> None:
    p = parse('say "go to bed" to Ann')
    assert p.text == "go to bed" and p.slots["recipient"] == ("ann",)


@pytest.mark.parametrize(
    ("text", "kind"),
    [
        ("what do you see?", "what_see"),
        ("what is in front of you", "what_see"),
        ("who is around?", "who_see"),
        ("who's here", "who_see"),
        ("where can I find the scissors?", "where"),
        ("do you know where the keys are", "where"),
        ("what's on the piano?", "what_on"),
        ("what do you see on the piano", "what_on"),
        ("is there a towel in the bathroom?", "can_see"),
        ("have you seen my keys", "can_see"),
        ("what's your name", "name"),
        ("who are you?", "name"),
        ("tell me what you see", "what_see"),
        ("any idea where the keys are?", "where"),
        ("where did Ann go", "where"),
        ("whose keys are these", "whose"),
        ("who owns the vase", "whose"),
        ("is there anything on the piano", "what_on"),
        ("do you see anything to drink", "can_see"),
    ],
)
def test_questions(text: str, kind: str) -> None:
    p = parse(text)
    assert (p.act, p.question) == ("question", kind)


@pytest.mark.parametrize(
    "text",
    ["hi", "Hello there!", "good morning", "good day", "hey robot", "hi, how are you?", "welcome back"],
)
def test_greetings(text: str) -> None:
    assert parse(text).act == "greeting"


def test_greeting_words_match_whole_words_only() -> None:
    # D11: "hi" must not fire inside "this" or "which".
    assert parse("this is which").act != "greeting"
    assert parse("hi, pick up the cup").intent == I.GRAB_OBJECT


@pytest.mark.parametrize(
    "text", ["don't pick up the cup", "please do not go to the kitchen", "never mind", "no"]
)
def test_negation(text: str) -> None:
    assert parse(text).act == "negated"


def test_robot_name_is_stripped_as_a_vocative() -> None:
    assert parse("Ari, grab the cup", robot_name="Ari").intent == I.GRAB_OBJECT


def test_unknown_input() -> None:
    assert parse("the weather is lovely today").act == "unknown"
    assert parse("").act == "unknown"


@pytest.mark.parametrize(
    ("text", "recipient", "goal"),
    [
        ("I want to go to the garage", ("me",), ("the", "garage")),
        ("Ann needs to get to the lobby", ("ann",), ("the", "lobby")),
        ("my mother has to go to the exit", ("my", "mother"), ("the", "exit")),
        ("we would like to go to the garden", ("me",), ("the", "garden")),
    ],
)
def test_someone_needing_to_go_somewhere_is_guided(
    text: str, recipient: tuple[str, ...], goal: tuple[str, ...]
) -> None:
    p = parse(text)
    assert (p.intent, p.slots["recipient"], p.slots["goal"]) == (I.GUIDE, recipient, goal)


@pytest.mark.parametrize(
    ("text", "act", "intent"),
    [
        ("thanks, now put the vase on the piano", "command", I.PLACE_OBJECT),
        ("thank you so much", "thanks", None),
        ("could you say hi to Ann for me", "command", I.GREET),
        ("I could use the vase", "command", I.BRING_OBJECT),
        ("can we play a quiz", "command", I.START_ACTIVITY),
        ("pop over to the garage", "command", I.MOVE_TO),
    ],
)
def test_preambles_and_indirect_requests(text: str, act: str, intent: str | None) -> None:
    p = parse(text)
    assert (p.act, p.intent) == (act, intent)
    if intent == I.GREET:
        assert p.slots["recipient"] == ("ann",)


@pytest.mark.parametrize(
    ("text", "kind"),
    [
        ("is anybody else here besides me", "who_see"),
        ("is there anyone in the room", "who_see"),
        ("could you find out where the vase is", "where"),
        ("check where the vase is", "where"),
    ],
)
def test_more_questions(text: str, kind: str) -> None:
    p = parse(text)
    assert (p.act, p.question) == ("question", kind)


@pytest.mark.parametrize(
    ("text", "slots"),
    [
        ("hang the coat in the hall", {"object": ("the", "coat"), "recipient": ("the", "hall")}),
        ("lay the shirt out on the bed", {"object": ("the", "shirt"), "recipient": ("the", "bed")}),
    ],
)
def test_more_ways_to_put_something_somewhere(text: str, slots: dict[str, tuple[str, ...]]) -> None:
    assert (parse(text).intent, parse(text).slots) == (I.PLACE_OBJECT, slots)


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        # a person's thing after a grabbing verb is the thing, not a recipient and a thing
        (
            "pick up Omar's scarf off the stool",
            "__intent_grab_object__",
            {"object": ("omar's", "scarf", "off", "the", "stool")},
        ),
        (
            "grab omars scarf from the stool",
            "__intent_grab_object__",
            {"object": ("omars", "scarf", "from", "the", "stool")},
        ),
    ],
)
def test_a_possessive_is_no_recipient_of_a_double_object(
    text: str, intent: str, slots: dict[str, tuple[str, ...]]
) -> None:
    p = parse(text)
    assert (p.intent, p.slots, p.double_object) == (intent, slots, False)


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        # where to go after a word that only says which way
        ("go outside to the patio", I.MOVE_TO, {"goal": ("the", "patio")}),
        ("head downstairs to the cellar", I.MOVE_TO, {"goal": ("the", "cellar")}),
        ("wait out in the porch", I.MOVE_TO, {"goal": ("the", "porch")}),
        ("go and stay over by the lift", I.MOVE_TO, {"goal": ("the", "lift")}),
        # a clause of time is no part of a referent
        ("hand Ola a towel while she dries off", I.BRING_OBJECT, {"rest": ("ola", "a", "towel")}),
        ("put the butter back before it melts", I.PLACE_OBJECT, {"object": ("the", "butter")}),
    ],
)
def test_which_way_and_clauses_of_time(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.intent, p.slots) == (intent, slots)


def test_a_clause_of_time_with_the_robot_as_subject_stays_part_of_the_request() -> None:
    # "after you wash it" asks for more than the bringing: not an adjunct to drop
    assert ("after", "you", "wash", "it") not in parse("bring me the mug after you wash it").adjuncts


@pytest.mark.parametrize(
    ("text", "message", "recipient"),
    [
        ("tell Ola it's time to go home", "it's time to go home", ("ola",)),
        ("remind Mr Sato he has to sign the form", "he has to sign the form", ("mr", "sato")),
        ("tell Ola to sit down", "please sit down", ("ola",)),
    ],
)
def test_a_message_with_a_subject_of_its_own(text: str, message: str, recipient: tuple[str, ...]) -> None:
    p = parse(text)
    assert (p.intent, p.text, p.slots["recipient"]) == (I.SAY, message, recipient)


@pytest.mark.parametrize(
    ("text", "recipient", "free"),
    [
        ("say to Ann that the bus is late", ("ann",), "the bus is late"),
        ("Say to Mr Ito that his room is ready.", ("mr", "ito"), "his room is ready"),
        ("say to Ann it is raining", ("ann",), "it is raining"),
        # a message whose subject is a noun phrase: the person told, then the clause
        ("tell Ann her parcel has arrived", ("ann",), "her parcel has arrived"),
        ("tell Ann her tomatoes are ready to pick", ("ann",), "her tomatoes are ready to pick"),
        ("tell my dad the plumber for the upstairs flat is here", ("my", "dad"),
         "the plumber for the upstairs flat is here"),
        ("tell Ann that her parcel is here", ("ann",), "her parcel is here"),
        ("tell Ann to bring her parcel", ("ann",), "please bring her parcel"),
        ("tell Ann from me that the bus is late", ("ann",), "the bus is late"),
        ("say to Ann on my behalf that the bus is late", ("ann",), "the bus is late"),
    ],
)  # fmt: skip
def test_whom_to_tell_and_what(text: str, recipient: tuple[str, ...], free: str) -> None:
    p = parse(text)
    assert (p.intent, p.slots.get("recipient"), p.text) == (I.SAY, recipient, free)


def test_say_to_someone_without_that_or_a_clause_is_not_read() -> None:
    # which words name the person and which are the message is not said ("say to Ann hello")
    assert parse("say to Ann hello").act == "unknown"
    assert parse("say to Ann").act == "unknown"


@pytest.mark.parametrize(
    ("text", "goal", "way"),
    [
        ("go down the allotment", ("the", "allotment"), None),
        ("pop round the back yard", ("the", "back", "yard"), None),
        ("nip up the attic", ("the", "attic"), None),
        ("go down to the cellar", ("the", "cellar"), None),  # "down" a particle
        ("go down the hall to the garage", ("the", "garage"), ("down", "the", "hall")),  # the way
        ("head up the stairs into the loft", ("the", "loft"), ("up", "the", "stairs")),
    ],
)
def test_a_particle_of_motion_before_a_noun_phrase_says_where_to(
    text: str, goal: tuple[str, ...], way: tuple[str, ...] | None
) -> None:
    p = parse(text)
    assert (p.intent, p.slots) == (I.MOVE_TO, {"goal": goal})
    assert way is None or way in p.adjuncts


def test_me_and_a_thing_to_a_place_is_the_thing_of_that_place_brought_to_me() -> None:
    p = parse("bring me the keys to the red car")
    assert (p.intent, p.slots) == (I.BRING_OBJECT, {"object": ("the", "keys", "to", "the", "red", "car"),
                                                    "recipient": ("me",)})  # fmt: skip


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        # how long is never where or whom
        ("go and wait in the hall for now", I.MOVE_TO, {"goal": ("the", "hall")}),
        ("stay by the gate for a bit", I.MOVE_TO, {"goal": ("the", "gate")}),
        ("take the fan for now to nadia", I.BRING_OBJECT, {"object": ("the", "fan"), "recipient": ("nadia",)}),
        # the particle of the way someone is shown or walked
        ("could you show nadia out to the porch", I.GUIDE, {"recipient": ("nadia",), "goal": ("the", "porch")}),
        ("walk me back up to the ward", I.GUIDE, {"recipient": ("me",), "goal": ("the", "ward")}),
        ("lead the guests down to the cellar", I.GUIDE, {"recipient": ("the", "guests"), "goal": ("the", "cellar")}),
    ],
)  # fmt: skip
def test_how_long_and_which_way_are_no_roles(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.act, p.intent) == ("command", intent)
    assert {k: v for k, v in p.slots.items() if k in {"object", "goal", "recipient"} & set(slots)} == slots
    assert "now" not in p.slots.get("recipient", ())


def test_out_of_the_way_is_no_place() -> None:
    # where not to be names no place to go: alone, the request says no intent
    assert parse("move out of the way").intent is None
    assert parse("get out of my way").intent is None
    assert parse("go out of the way to the shed").slots == {"goal": ("the", "shed")}


@pytest.mark.parametrize(
    ("text", "slots"),
    [
        # the place before "back" says which thing, the one after it where it goes
        (
            "put the goggles on the front bench back on the shelf",
            {"object": ("the", "goggles", "on", "the", "front", "bench"), "recipient": ("the", "shelf")},
        ),
        ("put the cup back on the shelf", {"object": ("the", "cup"), "recipient": ("the", "shelf")}),
        # the way between the person and where they go is an adjunct
        ("take aisha down the corridor to the staff room", {"object": ("aisha",), "recipient": ("the", "staff", "room")}),
        # a dative before the thing, which has a possessive of its own
        ("give to Fenna her keys", {"recipient": ("fenna",), "object": ("her", "keys")}),
    ],
)
def test_which_thing_where_it_goes_and_the_way(text: str, slots: dict[str, tuple[str, ...]]) -> None:
    assert parse(text).slots == slots


def test_the_way_is_said_apart_from_the_roles() -> None:
    assert parse("take aisha down the corridor to the staff room").adjuncts == (("down", "the", "corridor"),)
    assert parse("bring the box down to the cellar").slots["recipient"] == ("the", "cellar")


def test_a_state_to_bring_a_thing_into_is_no_intent_of_the_robots() -> None:
    assert parse("get the room ready").act == "unknown"


def test_a_question_after_a_greeting_greets_too_and_after_hey_only_asks() -> None:
    p = parse("hello robot whats your name", "robot")
    assert (p.act, p.question, p.greeted) == ("question", "name", True)
    assert not parse("hey robot whos at the gate", "robot").greeted


@pytest.mark.parametrize("text", ["take the stapler to", "give the stapler to", "go to"])
def test_a_role_cut_short_is_asked_for_never_dropped(office: KB, text: str) -> None:
    # ("take the stapler to" was a grab: the cut-short "to" dropped)
    out = say(office, text)
    assert out.intent is None and out.clarify


@pytest.mark.parametrize(
    "text",
    ["if Declan comes by, give him the menu", "if i nod off could you put my book on the table",
     "if the kettle boils pour me a tea"],
)  # fmt: skip
def test_a_request_for_when_something_happens_is_no_request_now(text: str) -> None:
    assert parse(text).act == "conditional"


@pytest.mark.parametrize(
    "text",
    ["if you could bring me the menu", "if possible bring me the menu", "if it's not too much trouble, bring me the menu",
     "if i could have the menu please"],
)  # fmt: skip
def test_a_polite_if_is_no_condition(text: str) -> None:
    assert parse(text).act != "conditional"


@pytest.mark.parametrize(
    "text",
    ["when the bell goes, could you take the register to the office", "after lunch take me to the day room",
     "when the train stops get my rucksack down", "after my appointment, bring me the novel",
     "say hi to her when she comes in", "bring Ana the menu once she sits down",
     "as soon as the kettle boils pour me a tea"],
)  # fmt: skip
def test_a_request_for_when_something_yet_to_happen_has_happened_is_no_request_now(text: str) -> None:
    assert parse(text).act == "conditional"


@pytest.mark.parametrize(
    "text",
    ["when you get a chance, bring me the menu", "bring me the menu when you can", "hand Femi a magazine while he waits",
     "put the milk back before it goes off", "when is lunch", "when did you last clean the kitchen",
     "once more, bring me the menu", "when you've got a minute can you start tidying the shelves",
     "once you're free, bring me the menu", "after that, bring me the menu", "once there, pick up the menu"],
)  # fmt: skip
def test_a_clause_of_time_that_says_no_later_moment_is_no_condition(text: str) -> None:
    assert parse(text).act != "conditional"


def test_a_request_under_a_condition_is_said_back_as_not_now(office: KB) -> None:
    out = say(office, "when Carol comes in, give her the pear")
    assert out.intent is None and out.more == () and "when Carol is here" in out.reply


@pytest.mark.parametrize("text", ["stop, don't go", "no stop dont go", "wait don't go"])
def test_stop_before_a_negated_request_is_the_negation(text: str) -> None:
    assert parse(text).act == "negated"


@pytest.mark.parametrize(
    "text",
    ["escort Carol until reaching the bathroom", "escort Carol until you get to the bathroom",
     "accompany Carol to the bathroom", "help Carol find the way to the bathroom",
     "help Carol find her way to the bathroom", "show Carol the way from the office to the bathroom",
     "one more thing: lead Carol to the bathroom"],
)  # fmt: skip
def test_who_is_guided_and_where_never_a_person_named_by_the_way(office: KB, text: str) -> None:
    out = say(office, text)
    assert (out.intent, out.roles) == (I.GUIDE, {"recipient": "person_carol", "goal": "bathroom"})


def test_a_person_to_be_taken_to_is_where_they_are(office: KB) -> None:
    office.update(["person_dan isIn hallway"])
    out = say(office, "take me to Dan")
    assert (out.intent, out.roles) == (I.GUIDE, {"recipient": "person_bob", "goal": "hallway"})


@pytest.mark.parametrize(
    "text",
    ["chat to Carol", "have a chat with Carol", "go and have a little chat with Carol", "keep Carol company",
     "keep Carol company for ten minutes, would you?", "go n have a natter with carol",
     "could you go and sit with Carol for a minute", "start a conversation with Carol",
     "strike up a conversation with Carol", "start talking to Carol"],
)  # fmt: skip
def test_engaging_said_as_company_or_a_chat(office: KB, text: str) -> None:
    out = say(office, text)
    assert (out.intent, out.roles) == (I.ENGAGE_WITH, {"recipient": "person_carol"})


def test_keeping_a_thing_is_no_company(office: KB) -> None:
    assert say(office, "keep the pear on the desk").intent is None


@pytest.mark.parametrize("text", ["bye", "goodbye robot", "see you later, Robbie", "thanks, bye", "thank you, see you"])
def test_a_farewell_is_read_said_to_the_robot_or_after_thanks(text: str) -> None:
    assert parse(text, robot_name="Robbie").act == "farewell"


def test_a_name_after_a_farewell_that_is_not_the_robots_is_no_farewell() -> None:
    assert parse("goodbye Ana", robot_name="Robbie").act != "farewell"


@pytest.mark.parametrize(
    ("text", "thing", "place"),
    [
        ("lay the towel over the bench", "towel", "bench"),
        ("hang the coat over the chair", "coat", "chair"),
        ("put the towel over by the bench", "towel", "bench"),  # a particle before a preposition
        ("put the towel back over on the bench", "towel", "bench"),
    ],
)
def test_over_says_where_a_thing_is_put_unless_a_particle(text: str, thing: str, place: str) -> None:
    p = parse(text)
    assert (p.intent, p.slots["object"], p.slots["recipient"]) == (I.PLACE_OBJECT, ("the", thing), ("the", place))


@pytest.mark.parametrize("text", ["yo robot. yo. stop", "hey robot, hey, stop"])
def test_a_call_for_attention_said_again_is_no_greeting_of_the_request_after_it(text: str) -> None:
    p = commands.parse(english(), text)
    assert (p.act, p.intent) == ("command", I.STOP_ACTIVITY)
    # a welcoming after the greeting is a request to greet someone, never a greeting said again
    p = commands.parse(english(), "hey tiago welcome mr dubois")
    assert (p.act, p.intent, p.slots) == ("command", I.GREET, {"recipient": ("mr", "dubois")})


@pytest.mark.parametrize(
    ("text", "rest"),
    [("take my husband his phone", ("my", "husband", "his", "phone")),
     ("get our youngest her coat", ("our", "youngest", "her", "coat"))],
)  # fmt: skip
def test_the_speakers_kin_before_a_phrase_of_its_own_is_a_double_object(text: str, rest: tuple[str, ...]) -> None:
    p = parse(text)
    assert (p.intent, p.slots, p.double_object) == (I.BRING_OBJECT, {"rest": rest}, True)


def test_the_speakers_own_thing_is_no_double_object() -> None:
    assert parse("take my phone to the table").double_object is False
