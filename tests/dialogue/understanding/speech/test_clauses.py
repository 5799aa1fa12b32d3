"""Run-on clauses of unpunctuated speech, and clauses that describe the thing asked for."""

import pytest

from dialogue import intents as I
from dialogue.history import Utterance
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.speech import clauses as cut
from kb import KB
from tests.dialogue.conftest import english, lexicon_of, scene_kb


def clauses(text: str) -> list[str]:
    return cut.clauses(english(), text)


def described(thing: tuple[str, ...], said: tuple[str, ...]) -> tuple[str, ...]:
    return cut.described(english(), thing, said)


def description(text: str) -> tuple[str, ...] | None:
    return cut.description(english(), text)

SPEAKER = "person_kim"


@pytest.mark.parametrize(
    ("text", "parts"),
    [
        # a subject pronoun and its verb start a clause
        ("could you carry my bag to mia shes waiting outside", ["could you carry my bag to mia", "shes waiting outside"]),
        ("hand me the torch i cant see a thing", ["hand me the torch", "i cant see a thing"]),
        ("fetch the kettle its boiled", ["fetch the kettle", "its boiled"]),
        # a name or a short noun phrase and a verb that agrees with it
        ("go to the lobby the taxi leaves soon", ["go to the lobby", "the taxi leaves soon"]),
        ("drive over to the gate omar wants a word", ["drive over to the gate", "omar wants a word"]),
        # a clause of reason starts at its conjunction
        ("bring the jug because she is thirsty", ["bring the jug", "because she is thirsty"]),
        ("take the mop to the hall theres a puddle", ["take the mop to the hall", "theres a puddle"]),
        # punctuation, and a polite request mid-utterance
        ("it is chilly, can I have the shawl", ["it is chilly", "can I have the shawl"]),
        ("it is chilly could you close it", ["it is chilly", "could you close it"]),
        # an indirect question said after another
        ("is tom in do you know where he went", ["is tom in", "do you know where he went"]),
        ("is the van back any idea where the keys are", ["is the van back", "any idea where the keys are"]),
        # a request after a remark, softened or after a word naming the listener
        ("shift out of the way a little perhaps wait by the porch",
         ["shift out of the way a little", "perhaps wait by the porch"]),
        ("youre blocking the hall pal go stand by the porch", ["youre blocking the hall pal", "go stand by the porch"]),
    ],
)  # fmt: skip
def test_a_clause_starts_where_a_subject_and_its_verb_start_again(text: str, parts: list[str]) -> None:
    assert clauses(text) == parts


@pytest.mark.parametrize(
    "text",
    [
        "give tom the reading glasses on the table",  # "glasses" is a plural noun, not a verb
        "tell him she is here",  # the clause is what to tell
        "can i have the jug",  # a question's order
        "bring me the cups the kids need",  # no verb agreeing with a singular noun phrase
        "put the box and its lid on the shelf",
        "do you know where the keys are",  # an indirect question at the start is the whole
        "what do you know about the van",
        "i just put it on the shelf",  # a subject's adverb, then its verb
        "you could maybe go to the porch",
        "thank the dear lady",
    ],
)
def test_one_clause_is_not_cut(text: str) -> None:
    assert clauses(text) == [text]


@pytest.mark.parametrize(
    ("clause", "said"),
    [
        ("its the tall one by the lamp", ("the", "tall", "one", "by", "the", "lamp")),
        ("i think they're in the hall", ("in", "the", "hall")),
        ("i left it on the step", ("on", "the", "step")),
        ("its broken", None),  # a remark, not where or which it is
        ("she's waiting", None),
    ],
)
def test_a_description_says_where_or_which_the_thing_is(clause: str, said: tuple[str, ...] | None) -> None:
    assert description(clause) == said


def test_described_qualifies_the_requests_phrase() -> None:
    assert described(("my", "bag"), ("the", "blue", "one", "by", "the", "door")) == (
        "my", "blue", "bag", "by", "the", "door")  # fmt: skip
    assert described(("the", "keys"), ("in", "the", "hall")) == ("the", "keys", "in", "the", "hall")


@pytest.fixture
def hall() -> KB:
    return scene_kb(
        None,
        f"{SPEAKER} rdf:type Human", f'{SPEAKER} rdfs:label "Kim"', f"myself sees {SPEAKER}",
        "person_mia rdf:type Human", 'person_mia rdfs:label "Mia"', "myself sees person_mia",
        "porch_1 rdf:type ZoneOfInterest", 'porch_1 rdfs:label "porch"',
        "clock_1 rdf:type Artifact", 'clock_1 rdfs:label "clock"', "myself sees clock_1",
        "torch_1 rdf:type Artifact", 'torch_1 rdfs:label "torch"', "myself sees torch_1",
        "bag_r rdf:type Artifact", 'bag_r rdfs:label "bag"', "bag_r hasColor red", "myself sees bag_r",
        "bag_b rdf:type Artifact", 'bag_b rdfs:label "bag"', "bag_b hasColor blue", "myself sees bag_b",
    )  # fmt: skip


def say(kb: KB, text: str) -> Outcome:
    return Interpreter(lexicon_of(kb), SPEAKER, [Utterance(SPEAKER, "hello")]).interpret(text)


@pytest.mark.parametrize(
    ("text", "intent", "roles"),
    [
        ("hand me the torch i cant see the clock", I.BRING_OBJECT, {"object": "torch_1", "recipient": SPEAKER}),
        ("could you walk mia to the porch her lift is here", I.GUIDE, {"recipient": "person_mia", "goal": "porch_1"}),
        ("greet mia shes just arrived", I.GREET, {"recipient": "person_mia"}),
        ("pass mia the torch the hall light is out", I.BRING_OBJECT, {"object": "torch_1", "recipient": "person_mia"}),
    ],
)  # fmt: skip
def test_a_remark_after_a_request_is_not_part_of_it(hall: KB, text: str, intent: str, roles: dict[str, str]) -> None:
    out = say(hall, text)
    assert (out.intent, out.roles) == (intent, roles), out.reply


@pytest.mark.parametrize(
    "text",
    [
        "could you move out of the way a bit maybe go over to the porch",
        "youre in the way mate go over by the porch",
        "get out of the way and go to the porch",
        "um shift out of my way love head to the porch",
    ],
)
def test_a_remark_or_where_not_to_be_before_the_request(hall: KB, text: str) -> None:
    out = say(hall, text)
    assert (out.intent, out.roles) == (I.MOVE_TO, {"goal": "porch_1"}), out.reply
    assert not out.more


def test_out_of_the_way_and_no_going_is_not_understood(hall: KB) -> None:
    # (the robot would be left in the way: the rules do not claim it)
    assert not say(hall, "move out of the way").understood
    assert not say(hall, "get out of the way and pick up the torch").understood


def test_a_description_after_a_request_picks_the_thing(hall: KB) -> None:
    out = say(hall, "um could you bring me my bag its the blue one on the hook")
    assert out.roles == {"object": "bag_b", "recipient": SPEAKER}, out.reply
    out = say(hall, "fetch me the bag i think its the red one")
    assert out.roles == {"object": "bag_r", "recipient": SPEAKER}, out.reply


def test_a_clause_run_into_a_phrase_never_names_its_last_noun(hall: KB) -> None:
    # "the clock" ends the phrase but is the remark's, not what to bring.
    out = say(hall, "bring me the torch i cant read the clock")
    assert out.roles.get("object") == "torch_1", out.reply


@pytest.mark.parametrize(
    ("said", "thing", "meant"),
    [
        ("it's Raf's", ("the", "red", "cap"), ("raf's", "red", "cap")),
        ("its Raf's", ("the", "cap"), ("raf's", "cap")),
        ("they're mine", ("the", "gloves"), ("my", "gloves")),
    ],
)
def test_a_clause_may_say_whose_the_thing_is(said: str, thing: tuple[str, ...], meant: tuple[str, ...]) -> None:
    more = description(said)
    assert more is not None and described(thing, more) == meant


def test_a_remark_with_someone_as_its_subject_is_a_clause_of_its_own(office: KB) -> None:
    assert clauses("can you pick up the mug someone left it here") == ["can you pick up the mug", "someone left it here"]
    out = Interpreter(lexicon_of(office), "person_bob").interpret("can you pick up the mug someone left it here")
    assert out.clarify and out.intent is None and "yellow" in out.reply


def test_a_tag_question_ends_the_request_it_follows() -> None:
    assert clauses("pick up my frame would you its fallen over") == [
        "pick up my frame would you", "its fallen over",
    ]  # fmt: skip
