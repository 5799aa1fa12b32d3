"""Speech-recogniser and chat style: what normalisation and the grammar make of it."""

import pytest

from dialogue import intents as I
from dialogue.understanding.parsed import Parse
from dialogue.understanding.requests import commands
from dialogue.understanding.speech import plain, repair
from dialogue.understanding.speech.repair import Cleaned
from kb import KB
from tests.dialogue.conftest import english
from tests.dialogue.understanding.test_interpret import say


def parse(text: str, robot_name: str = "") -> Parse:
    """The grammar's reading of the words (in English)."""
    return commands.parse(english(), text, robot_name)


def expanded(text: str) -> list[str]:
    return plain.expanded(english(), text)


def strip_politeness(words: list[str], robot_name: str = "") -> list[str]:
    return plain.strip_politeness(english(), words, robot_name)


def cleaned(text: str) -> Cleaned:
    return repair.cleaned(english(), text)


def normalise(text: str) -> list[str]:
    return repair.normalise(english(), text)


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("wheres my phone", "where is my phone"),
        ("im thirsty shes here", "i am thirsty she is here"),
        ("put the uh cup erm on the table", "put the cup on the table"),
        ("put the put the knife on table four", "put the knife on table four"),
        ("pick up the the red jumper", "pick up the red jumper"),
        ("bring me the uh no wait put the candle on the table", "put the candle on the table"),
        ("take the beaker to uh sorry i mean put the beaker on the bench", "put the beaker on the bench"),
        ("pick up the cup you know the blue one", "pick up the cup the blue one"),
        ("do you know where the keys are", "do you know where the keys are"),  # not a filler here
        ("table 4 4", "table 4 4"),  # numbers are not stutters
        # chat and recogniser spellings
        ("can u pass the salt theyre waiting", "can you pass the salt they are waiting"),
        ("how many mugs r there", "how many mugs are there"),
        ("grab my keys b4 u go", "grab my keys before you go"),
        ("fetch the tray n bring it bk rn", "fetch the tray and bring it back right now"),
        ("pls get sth to eat", "please get something to eat"),
        ("cld u grab em lol", "could you grab them"),
        # a word that only announces the number after it
        ("go to gate number nine", "go to gate nine"),
        ("go to room no 4", "go to room 4"),
        ("no one is there", "no one is there"),
    ],
)
def test_normalise(text: str, words: str) -> None:
    assert " ".join(normalise(text)) == words


def test_cleaned_keeps_text_without_repairs() -> None:
    assert cleaned('Say "Hello, Tom!" to Tom').text == 'Say "Hello, Tom!" to Tom'
    assert cleaned("put the put the cup down") == Cleaned("put the cup down")


@pytest.mark.parametrize(
    ("text", "meant", "taken_back"),
    [
        # a request said again: what was taken back is kept as context for the new one's pronouns
        ("hand ravi the uh no wait hand him the stapler", "hand him the stapler", "hand ravi the"),
        ("where is the ferry actually could you walk me there", "could you walk me there", "where is the ferry"),
        # a noun phrase said again replaces the last one; "one" is the head it replaces
        ("grab the red scarf no the green one", "grab the green scarf", "grab the red scarf"),
        ("put the pen sorry i mean the pencil in the tray", "put the pencil in the tray", "put the pen"),
        ("fetch the tea oh wait the coffee please", "fetch the coffee", "fetch the tea"),
        # no repair: "no" inside a phrase, or nothing that could be said again
        ("make it a tea with no milk", "make it a tea with no milk", ""),
        ("no thanks", "no thanks", ""),
    ],
)
def test_a_self_repair_says_again_a_request_or_its_last_phrase(text: str, meant: str, taken_back: str) -> None:
    assert cleaned(text) == Cleaned(meant, taken_back)


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("its on the shelf", "it is on the shelf"),
        ("its the tall one", "it is the tall one"),
        ("bin it its empty", "bin it it is empty"),
        ("its stopped raining", "it is stopped raining"),
        ("the kettle and its lid", "the kettle and its lid"),  # a possessive before its noun
        ("its handle is loose", "its handle is loose"),
    ],
)
def test_its_without_apostrophe_is_it_is_where_no_noun_follows(text: str, words: str) -> None:
    assert " ".join(expanded(text)) == words


def test_a_message_keeps_the_words_said_after_it_but_not_the_politeness_to_the_robot() -> None:
    assert parse("tell ravi that the taxi is outside now please").text == "the taxi is outside now"
    assert parse("Tell Ravi the bus leaves again at noon, thanks").text == "the bus leaves again at noon"
    assert parse("tell ravi dinner is ready uh").text == "dinner is ready"
    assert parse("tell ravi I am coming too").text == "I am coming too"


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        ("john can you go to the bathroom", I.MOVE_TO, {"goal": ("the", "bathroom")}),
        ("michael go to the kitchen", I.MOVE_TO, {"goal": ("the", "kitchen")}),
        ("hey tiago pick up the red jumper", I.GRAB_OBJECT, {"object": ("the", "red", "jumper")}),
        ("listen go to the kitchen", I.MOVE_TO, {"goal": ("the", "kitchen")}),
        ("be a dear and fetch me the tape", I.BRING_OBJECT, {"object": ("the", "tape"), "recipient": ("me",)}),
        ("would you mind terribly showing me where the bathroom is", I.GUIDE,
         {"recipient": ("me",), "goal": ("the", "bathroom")}),
        ("I was wondering if you could get me the map", I.BRING_OBJECT,
         {"object": ("the", "map"), "recipient": ("me",)}),
        ("off you go to the shed", I.MOVE_TO, {"goal": ("the", "shed")}),
        ("go close to the window", I.MOVE_TO, {"goal": ("the", "window")}),
        ("go quickly to the corner", I.MOVE_TO, {"goal": ("the", "corner")}),
        ("please enter the bathroom", I.MOVE_TO, {"goal": ("the", "bathroom")}),
        ("I'm absolutely parched", I.BRING_OBJECT, {"object": ("drink",), "recipient": ("me",)}),
        ("im starving", I.BRING_OBJECT, {"object": ("food",), "recipient": ("me",)}),
        ("take the cup next to the pear", I.GRAB_OBJECT, {"object": ("the", "cup", "beside", "the", "pear")}),
        ("help me get to the bathroom, would you?", I.GUIDE, {"recipient": ("me",), "goal": ("the", "bathroom")}),
        ("put it over there", I.PLACE_OBJECT, {"object": ("it",), "recipient": ("there",)}),
        ("i really need you to bring me the cup", I.BRING_OBJECT, {"object": ("the", "cup"), "recipient": ("me",)}),
    ],
)  # fmt: skip
def test_requests(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.act, p.intent) == ("command", intent)
    assert {k: v for k, v in p.slots.items() if k in slots} == slots


@pytest.mark.parametrize(
    "text", ["do you like music?", "do robots ever get tired", "do you think this colour suits me"]
)
def test_yes_no_questions_are_never_activities(text: str) -> None:
    assert parse(text).intent is None


def test_a_lead_and_a_thanks_of_their_own_are_politeness() -> None:
    assert parse("right could you grab the broom ta").slots == {"object": ("the", "broom")}
    assert parse("pass me the broom cheers").slots == {"object": ("the", "broom"), "recipient": ("me",)}


@pytest.mark.parametrize(
    ("text", "words"),
    [
        # "we"/"us" is the speaker: "could we get X" asks for X, as "can I get X" does
        ("could we get the menu", "could we get the menu"),
        ("can we have two pies", "can we have two pies"),
        # ...but going somewhere, or a thing for someone else, is a request to the robot
        ("could we get over to the door", "get over to the door"),
        ("can we get the pie to nadia", "get the pie to nadia"),
        # "for now" says how long: its "now" is no politeness
        ("wait by the door for now", "wait by the door for now"),
        ("wait by the door now", "wait by the door"),
        # what adds a request to the ones before it changes nothing of it
        ("bring theo the biscuit tin as well", "bring theo the biscuit tin"),
        ("fetch me the saw too please", "fetch me the saw"),
        # "real quick" is how soon, all of it
        ("grab me a cola real quick", "grab me a cola"),
        ("bring me the pump right quick", "bring me the pump"),
        # a chore said of someone is asked of the robot
        ("someone needs to put the flip flops in the crate", "put the flip flops in the crate"),
        ("somebody ought to put the sack on the trolley", "put the sack on the trolley"),
        ("could somebody let dmitri know the showers are leaking", "let dmitri know the showers are leaking"),
        # formal and old-fashioned openings
        ("but i wonder whether you might fetch my coat from the chair", "fetch my coat from the chair"),
        ("might you pick up that pencil", "pick up that pencil"),
        ("would you be good enough to escort ben to the hallway", "escort ben to the hallway"),
        # a thing asked for if it is ready, or if it can be: asked for now ("when it's ready" waits)
        ("bring me my cards now if they're ready", "bring me my cards"),
        ("fetch the cake if it's ready", "fetch the cake"),
        ("bring me the bill if possible", "bring me the bill"),
    ],
)
def test_what_politeness_leaves_of_a_request(text: str, words: str) -> None:
    assert " ".join(strip_politeness(normalise(text))) == words


@pytest.mark.parametrize(
    ("text", "intent", "slots"),
    [
        ("excuse me could we get the um the pie please", I.BRING_OBJECT,
         {"object": ("the", "pie"), "recipient": ("me",)}),
        ("could we have the menu", I.BRING_OBJECT, {"object": ("the", "menu"), "recipient": ("me",)}),
        ("pass us the salt", I.BRING_OBJECT, {"object": ("the", "salt"), "recipient": ("me",)}),
        # "I'll have my X", and a need said by what the speaker cannot reach
        ("i'll have my business cards now if they're ready", I.BRING_OBJECT,
         {"object": ("my", "business", "cards"), "recipient": ("me",)}),
        ("i can't reach the watering can", I.BRING_OBJECT, {"object": ("the", "watering", "can"), "recipient": ("me",)}),
    ],
)  # fmt: skip
def test_what_we_ask_for_is_brought_to_the_speaker(text: str, intent: str, slots: dict[str, tuple[str, ...]]) -> None:
    p = parse(text)
    assert (p.intent, p.slots) == (intent, slots)


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("whats on the desk atm", "what is on the desk"),  # chat: "at the moment", longest first
        ("who is at home right now", "who is at home"),  # "right now" before its "now"
        ("where is the atm", "where is the atm"),  # after a determiner an abbreviation is a noun
        ("robot you must go to the balcony", "go to the balcony"),  # a modal said to the robot
        ("you have to go to the balcony", "go to the balcony"),
        ("take my calculator to sir", "take my calculator to sir"),  # whom, not a tag
        ("take the calculator over there sir", "take the calculator over there"),
        ("idk just go to the shed tbh", "i don't know just go to the shed"),
    ],
)
def test_chat_modals_and_what_politeness_at_the_end_leaves(text: str, words: str) -> None:
    assert " ".join(strip_politeness(normalise(text), "robot")) == words


@pytest.mark.parametrize(
    ("text", "words"),
    [("go ovr to the counter", "go over to the counter"), ("cn u bring it", "can you bring it"),
     ("wat's on the table", "what is on the table")],
)
def test_more_chat_words(text: str, words: str) -> None:
    assert expanded(text) == words.split()


@pytest.mark.parametrize(
    ("text", "meant"),
    [
        ("pick up me zimmer frame", "pick up my zimmer frame"),
        ("fetch me me cardigan", "fetch me my cardigan"),
        ("bring me the cardigan", "bring me the cardigan"),  # "me" the recipient stays
    ],
)
def test_me_said_for_my_before_a_noun(text: str, meant: str) -> None:
    assert cleaned(text).text == meant


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("pick up the what's it called the tongs", "pick up the tongs"),
        ("bring me the what do you call it the thingy the stapler", "bring me the stapler"),
        ("what is it called", "what is it called"),  # said first: a question
    ],
)
def test_a_word_searched_for_mid_request_is_dropped(text: str, words: str) -> None:
    assert " ".join(normalise(text)) == words


def test_a_word_searched_for_is_no_question_about_a_name(office: KB) -> None:
    out = say(office, "pick up the... what's it called... the thingy, the pear")
    assert (out.intent, out.roles) == (I.GRAB_OBJECT, {"object": "pear_1"})


@pytest.mark.parametrize(
    ("text", "words"),
    [("take it ower tae her", "take it over to her"), ("gie her the orange juice", "give her the orange juice"),
     ("gonnae bring us the kettle", "will you bring us the kettle"), ("haud on", "hold on")],
)  # fmt: skip
def test_scots_words_are_the_english_they_say(text: str, words: str) -> None:
    assert " ".join(plain.expanded(english(), text)) == words


def test_scots_to_is_never_the_tea(office: KB) -> None:
    office.update(['tea_1 rdf:type Artifact', 'tea_1 rdfs:label "box of teabags"', "myself sees tea_1"])
    out = say(office, "Carol's wanting the pear, take it ower tae her.")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_carol"})


def test_a_chat_word_written_with_a_capital_is_a_name(office: KB) -> None:
    # "Fae" and "Tae" are names as well as Scots words: written with a capital, the name
    assert plain.expanded(english(), "bring the pear to Fae") == ["bring", "the", "pear", "to", "fae"]
    assert plain.expanded(english(), "bring the pear tae her") == ["bring", "the", "pear", "to", "her"]
    office.update(["person_fae rdf:type Human", 'person_fae rdfs:label "Fae"', "myself sees person_fae"])
    out = say(office, "bring the pear to Fae")
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "pear_1", "recipient": "person_fae"})


@pytest.mark.parametrize(
    ("text", "words"),
    [("where have they gone and put my stick", "where have they put my stick"),
     ("she has been and bought milk", "she has bought milk"),
     ("once carol has gone and dan is back", "once carol has gone and dan is back")],  # two events
)  # fmt: skip
def test_gone_and_is_a_filler_only_before_a_verb(text: str, words: str) -> None:
    assert " ".join(plain.without_fillers(english(), text.split())) == words
