"""The rules claim a turn only when they understood it: each class of wrong claim seen on the
case sets, on scenes and sentences of its own."""

from dialogue.history import ASSISTANT_USER_ID, Utterance
from dialogue.understanding.interpret import Interpreter
from dialogue.understanding.outcome import Outcome
from kb import KB
from tests.dialogue.conftest import lexicon_of, scene_kb

SPEAKER = "person_kim"
_PEOPLE = (f"{SPEAKER} rdf:type Human", f'{SPEAKER} rdfs:label "Kim"', f"myself sees {SPEAKER}")


def say(kb: KB, text: str, history: list[tuple[str, str]] | None = None) -> Outcome:
    turns = [Utterance(SPEAKER if who == "user" else ASSISTANT_USER_ID, t) for who, t in history or []]
    return Interpreter(lexicon_of(kb), SPEAKER, turns).interpret(text)


def scene(*facts: str) -> KB:
    return scene_kb(None, *_PEOPLE, *facts)


def test_where_says_every_spatial_fact_not_only_support_and_zone() -> None:
    kb = scene(
        "boots_1 rdf:type Artifact", 'boots_1 rdfs:label "wellies"', "myself sees boots_1",
        "door_1 rdf:type Artifact", 'door_1 rdfs:label "back door"', "boots_1 isNextTo door_1",
        "bag_1 rdf:type Artifact", 'bag_1 rdfs:label "kit bag"', "myself sees bag_1",
        "bench_1 rdf:type Artifact", 'bench_1 rdfs:label "bench"', "bag_1 isBelow bench_1",
    )  # fmt: skip
    out = say(kb, "wheres my wellies")
    assert out.understood and out.intent is None
    assert "next to the back door" in out.reply
    assert "under the bench" in say(kb, "where is the kit bag").reply


def test_a_compound_name_is_its_head_not_a_thing_on_it() -> None:
    # "the spice rack" is the rack, not the spice jar standing on it (whose support is the rack).
    kb = scene(
        "rack_1 rdf:type Artifact", 'rack_1 rdfs:label "spice rack"', "myself sees rack_1",
        "jar_1 rdf:type Artifact", 'jar_1 rdfs:label "jar of spice"', "jar_1 isOn rack_1", "myself sees jar_1",
        "mint_1 rdf:type Artifact", 'mint_1 rdfs:label "mint"', "mint_1 isOn rack_1",
    )  # fmt: skip
    out = say(kb, "what is on the spice rack")
    assert not out.clarify, out.reply
    assert "mint" in out.reply
    assert say(kb, "pick up the spice rack").roles == {"object": "rack_1"}


def test_a_closed_compound_said_apart_beats_a_name_that_only_shares_its_head() -> None:
    # "tool box" is the toolbox; the lunch box is a box too, but only by its last word.
    kb = scene(
        "tb_1 rdf:type Artifact", 'tb_1 rdfs:label "toolbox"', "myself sees tb_1",
        "lb_1 rdf:type Artifact", 'lb_1 rdfs:label "lunch box"', "myself sees lb_1",
    )  # fmt: skip
    out = say(kb, "uh grab the tool box by the wheelbarrow")
    assert out.roles == {"object": "tb_1"}, out.reply


def test_a_plural_place_is_each_of_them_not_a_question_which_one() -> None:
    kb = scene(
        "d1 rdf:type Artifact", 'd1 rdfs:label "top drawer"', "myself sees d1",
        "d2 rdf:type Artifact", 'd2 rdfs:label "bottom drawer"', "myself sees d2",
        "spoon_1 rdf:type Artifact", 'spoon_1 rdfs:label "spoon"', "spoon_1 isOn d1",
        "fork_1 rdf:type Artifact", 'fork_1 rdfs:label "fork"', "fork_1 isOn d2",
    )  # fmt: skip
    out = say(kb, "whats on the drawers")
    assert not out.clarify and out.understood, out.reply
    assert "spoon" in out.reply and "fork" in out.reply
    assert say(kb, "whats on the drawer").clarify  # one of them, unsaid which: ask


def test_a_word_of_a_label_is_a_head_with_modifiers_checked() -> None:
    # "the kettle on the sideboard" for the "dictaphone recorder": a word of its label, with a place.
    kb = scene(
        "k_1 rdf:type Artifact", 'k_1 rdfs:label "dictaphone recorder"', "myself sees k_1",
        "sb_1 rdf:type Artifact", 'sb_1 rdfs:label "sideboard"', "k_1 isOn sb_1", "myself sees sb_1",
        "k_1 belongsTo person_lee", "person_lee rdf:type Human", 'person_lee rdfs:label "Lee"',
    )  # fmt: skip
    assert "Lee" in say(kb, "whose dictaphone is that on the sideboard").reply
    assert say(kb, "grab the dictaphone off the sideboard").roles == {"object": "k_1"}


def test_fetching_something_for_someone_is_bringing_it_to_them() -> None:
    kb = scene(
        "jar_1 rdf:type Artifact", 'jar_1 rdfs:label "honey jar"', "myself sees jar_1",
        "person_lee rdf:type Human", 'person_lee rdfs:label "Lee"', "myself sees person_lee",
    )  # fmt: skip
    out = say(kb, "could you get the honey jar down for lee")
    assert (out.intent, out.roles) == ("__intent_bring_object__", {"object": "jar_1", "recipient": "person_lee"})


def _garden() -> KB:
    return scene(
        "pond_1 rdf:type ZoneOfInterest", 'pond_1 rdfs:label "koi pond"',
        "shed_1 rdf:type ZoneOfInterest", 'shed_1 rdfs:label "potting shed"',
    )  # fmt: skip


def test_take_us_there_guides_to_the_place_just_spoken_of() -> None:
    out = say(_garden(), "sorry wheres the koi pond could you take me there")
    assert (out.intent, out.roles) == ("__intent_guide__", {"recipient": SPEAKER, "goal": "pond_1"}), out.reply


def test_lead_the_way_guides_the_speaker_to_the_place_just_spoken_of() -> None:
    out = say(_garden(), "The potting shed sounds lovely. Show me the way?")
    assert (out.intent, out.roles) == ("__intent_guide__", {"recipient": SPEAKER, "goal": "shed_1"}), out.reply
    assert say(_garden(), "lead the way to the koi pond").roles == {"recipient": SPEAKER, "goal": "pond_1"}


def test_lead_the_way_after_naming_someone_guides_them() -> None:
    kb = scene_kb(None, *_PEOPLE, "person_lee rdf:type Human", 'person_lee rdfs:label "Lee"',
                  "myself sees person_lee", "shed_1 rdf:type ZoneOfInterest", 'shed_1 rdfs:label "potting shed"')
    out = say(kb, "Lee wants to see the potting shed. Would you lead the way?")
    assert (out.intent, out.roles) == ("__intent_guide__", {"recipient": "person_lee", "goal": "shed_1"}), out.reply


def test_a_description_of_a_person_is_not_the_speaker() -> None:
    kb = scene(
        "person_x rdf:type Human", 'person_x rdfs:label "visitor"', "myself sees person_x",
        f'{SPEAKER} rdfs:label "visitor"', "card_1 rdf:type Artifact", 'card_1 rdfs:label "postcard"',
        "myself sees card_1",
    )  # fmt: skip
    out = say(kb, "give this postcard to the visitor by the window")
    assert out.roles == {"object": "card_1", "recipient": "person_x"}, out.reply


def test_the_colour_one_with_nothing_said_before_is_the_one_thing_of_that_colour() -> None:
    kb = scene(
        "m1 rdf:type Artifact", 'm1 rdfs:label "beaker"', "m1 hasColor blue", "myself sees m1",
        "m2 rdf:type Artifact", 'm2 rdfs:label "flask"', "m2 hasColor red", "myself sees m2",
        "m3 rdf:type Artifact", 'm3 rdfs:label "funnel"', "m3 hasColor red", "myself sees m3",
    )  # fmt: skip
    assert say(kb, "uh hand me the blue one").roles == {"object": "m1", "recipient": SPEAKER}
    assert say(kb, "hand me the red one").clarify  # two red things: ask which


def _bays() -> KB:
    return scene(
        "b4 rdf:type Artifact", 'b4 rdfs:label "loading bay four"', "myself sees b4",
        "b9 rdf:type Artifact", 'b9 rdfs:label "loading bay nine"', "myself sees b9",
    )  # fmt: skip


def test_a_number_misheard_in_a_name_is_a_guess_not_a_claim_of_understanding() -> None:
    # "bay for", "bay mine": a recogniser slip of "four", "nine". Read as that name, which the rules
    # mark as a guess (less sure; a hybrid model leaves it to its model, see tests/dialogue/llm).
    for said, meant in (("go to the loading bay for", "b4"), ("go to the loading bay mine", "b9")):
        out = say(_bays(), said)
        assert (out.intent, out.roles, out.guessed) == ("__intent_move_to__", {"goal": meant}, True), said
        assert out.confidence < 0.9


def test_a_phrase_whose_last_word_is_no_slip_of_a_name_is_not_claimed() -> None:
    # "bay fine": which bay is not said ("fine" is no slip of "four" or "nine"): no guess, no question.
    out = say(_bays(), "go to the loading bay fine")
    assert not out.understood and not out.clarify and out.intent is None, out.reply
    assert say(_bays(), "go to the loading bay").clarify


def _terminal() -> KB:
    return scene(
        "lifts_1 rdf:type ZoneOfInterest", 'lifts_1 rdfs:label "lifts"',
        "person_noor rdf:type Human", 'person_noor rdfs:label "Noor"', "myself sees person_noor",
        "person_sam rdf:type Human", 'person_sam rdfs:label "Sam"', "myself sees person_sam",
        "flask_1 rdf:type Artifact", 'flask_1 rdfs:label "flask"', "myself sees flask_1",
        "ball_r rdf:type Artifact", 'ball_r rdfs:label "ball"', "ball_r hasColor red", "myself sees ball_r",
        "ball_g rdf:type Artifact", 'ball_g rdfs:label "ball"', "ball_g hasColor green", "myself sees ball_g",
    )  # fmt: skip


def test_needing_a_place_is_being_taken_there() -> None:
    out = say(_terminal(), "i need the lifts")
    assert (out.intent, out.roles) == ("__intent_guide__", {"recipient": SPEAKER, "goal": "lifts_1"}), out.reply
    out = say(_terminal(), "um i need the uh the lifts can you take me")
    assert (out.intent, out.roles) == ("__intent_guide__", {"recipient": SPEAKER, "goal": "lifts_1"}), out.reply
    # with no place spoken of, "take me" asks where (a question, not a guess)
    out = say(_terminal(), "can you take me")
    assert out.clarify and out.reply == "Where should I take you?"


def test_an_answer_with_a_tag_word_completes_the_request() -> None:
    history = [("user", "pass me the ball"), ("robot", "Which ball: the red one or the green one?")]
    out = say(_terminal(), "the green one pal", history)
    assert out.roles == {"object": "ball_g", "recipient": SPEAKER}, out.reply


def test_a_request_redirected_instead_keeps_the_thing_spoken_of() -> None:
    history = [("user", "give sam the flask"), ("robot", "OK, I will bring the flask to Sam.")]
    out = say(_terminal(), "actually no give it to noor instead", history)
    assert out.roles == {"object": "flask_1", "recipient": "person_noor"}, out.reply


def test_a_second_place_that_the_first_is_not_on_is_where_to_put_it() -> None:
    kb = scene(
        "shelf_1 rdf:type Artifact", 'shelf_1 rdfs:label "shelf"', "myself sees shelf_1",
        "desk_1 rdf:type Artifact", 'desk_1 rdfs:label "desk"', "myself sees desk_1",
        "lamp_1 rdf:type Artifact", 'lamp_1 rdfs:label "lamp"', "lamp_1 isOn desk_1", "myself sees lamp_1",
        "vase_1 rdf:type Artifact", 'vase_1 rdfs:label "vase"', "myself sees vase_1",
    )  # fmt: skip
    # the lamp is on the desk, not the shelf: "on the shelf" is where the vase goes
    out = say(kb, "put the vase next to the lamp on the shelf")
    assert (out.intent, out.roles) == ("__intent_place_object__", {"object": "vase_1", "recipient": "shelf_1"})
    out = say(kb, "put the vase next to the lamp on the desk")
    assert out.roles == {"object": "vase_1", "recipient": "lamp_1"}, out.reply


def test_give_me_a_hand_to_a_place_is_guiding() -> None:
    out = say(_terminal(), "can you give me a hand to the lifts")
    assert (out.intent, out.roles) == ("__intent_guide__", {"recipient": SPEAKER, "goal": "lifts_1"}), out.reply


def test_a_second_phrase_of_one_says_which_the_first_is() -> None:
    out = say(_terminal(), "hand me the ball the green one")
    assert out.roles == {"object": "ball_g", "recipient": SPEAKER}, out.reply


def test_a_person_where_a_thing_is_wanted_is_not_understood() -> None:
    # "go and get him": no intent fetches a person; nothing is claimed (no "what do you mean by him")
    out = say(_terminal(), "noor is in the lobby go and get him")
    assert not out.understood and out.intent is None and not out.clarify, out.reply


def test_what_is_elsewhere_is_said_with_where_the_kb_puts_it() -> None:
    kb = _terminal()
    kb.update(["hall_1 rdf:type ZoneOfInterest", 'hall_1 rdfs:label "hall"', "flask_1 isIn hall_1"])
    assert say(kb, "is the flask in the lifts").reply == "No, as far as I know the flask is in the hall."
    assert say(_terminal(), "can you see the flask anywhere").reply.startswith("Yes, I see")


def test_which_thing_is_mine_says_whose_each_is() -> None:
    kb = _terminal()
    kb.update(["ball_r belongsTo person_kim", "ball_g belongsTo person_noor"])
    reply = say(kb, "which ball is mine").reply
    assert "red ball" in reply and "is yours" in reply and "Noor's" in reply, reply


def test_a_greeting_followed_by_what_is_not_understood_is_not_claimed_as_a_greeting() -> None:
    out = say(_terminal(), "hey robot the striped bag is mine can you bring it over")
    assert not out.understood and out.intent is None, out.reply
    assert say(_terminal(), "good morning noor").intent == "__intent_greet__"


def test_a_place_said_again_replaces_the_last_place() -> None:
    kb = _terminal()
    kb.update(["shelf_1 rdf:type Artifact", 'shelf_1 rdfs:label "shelf"', "myself sees shelf_1",
               "desk_1 rdf:type Artifact", 'desk_1 rdfs:label "desk"', "myself sees desk_1"])
    out = say(kb, "put the flask on the shelf no wait on the desk")
    assert (out.intent, out.roles) == ("__intent_place_object__", {"object": "flask_1", "recipient": "desk_1"})


def test_the_thing_meant_not_the_one_it_is_not() -> None:
    out = say(_terminal(), "hand me the red ball not the green one")
    assert out.roles == {"object": "ball_r", "recipient": SPEAKER}, out.reply


def test_a_position_word_does_not_make_a_named_thing_ambiguous() -> None:
    kb = scene(
        "b1 rdf:type Artifact", 'b1 rdfs:label "box of nails"', "myself sees b1",
        "b2 rdf:type Artifact", 'b2 rdfs:label "box of screws"', "myself sees b2",
        "s1 rdf:type Artifact", 's1 rdfs:label "shelf"', "myself sees s1",
    )  # fmt: skip
    out = say(kb, "pop the box of nails back on the shelf")
    assert (out.intent, out.roles) == ("__intent_place_object__", {"object": "b1", "recipient": "s1"}), out.reply


def _classroom() -> KB:
    return scene(
        "m_b rdf:type Artifact", 'm_b rdfs:label "marker"', "m_b hasColor blue", "myself sees m_b",
        "m_r rdf:type Artifact", 'm_r rdfs:label "marker"', "m_r hasColor red", "myself sees m_r",
        "sheets_1 rdf:type Artifact", 'sheets_1 rdfs:label "worksheets"', "myself sees sheets_1",
        "person_sam rdf:type Human", 'person_sam rdfs:label "Sam"', "myself sees person_sam",
    )  # fmt: skip


def test_handing_out_is_no_bringing_to_the_speaker() -> None:
    out = say(_classroom(), "can you hand out the worksheets")
    assert not out.understood and out.intent is None, out.reply
    assert say(_classroom(), "hand me the worksheets").roles == {"object": "sheets_1", "recipient": SPEAKER}


def test_a_person_brought_to_a_person_is_not_claimed() -> None:
    out = say(_classroom(), "bring sam here")
    assert not out.understood and out.intent is None, out.reply


def test_a_place_named_only_by_a_position_word_is_left_to_a_model() -> None:
    out = say(_classroom(), "bring the worksheets to the front")
    assert not out.understood and out.intent is None, out.reply


def test_things_sharing_a_name_are_told_apart_by_colour() -> None:
    assert say(_classroom(), "how many markers are there").reply == "I see two markers: the blue one and the red one."
    assert "the red marker" in say(_classroom(), "which marker is red").reply


def test_a_word_nothing_accounts_for_is_a_doubt_not_an_absent_thing() -> None:
    kb = scene("mop_1 rdf:type Artifact", 'mop_1 rdfs:label "mop"', "myself sees mop_1",
               "hall rdf:type ZoneOfInterest", 'hall rdfs:label "hall"')  # fmt: skip
    # "zorp" is neither a name of the KB nor a word of English: saying "I don't see any zorp" would
    # claim to know what it is
    for text in ("fetch the zorp", "pick up the blorgs", "go to the zorp", "how many zorps are there"):
        assert not say(kb, text).understood, text
    # an English noun the KB names nothing with is a doubt too: "bunny" may be the toy rabbit,
    # "remove" the remote misheard; saying "I don't see any" would claim there is none
    for text in ("fetch the hammer", "get my bunny", "bring me the remove"):
        assert not say(kb, text).understood, text
    # words the KB names, nothing here fitting them all, are a thing the robot does not see: an answer
    kb.add(["mop_1 hasColor blue"])
    absent = say(kb, "fetch the red mop")
    assert absent.understood and absent.reply == "Sorry, I don't see any red mop."
    # a person's name the KB does not know is said to be unknown, but as a doubt: a recogniser's
    # spelling of a name ("chevonne" for Siobhan) is for a model to read in the situation
    unknown = say(kb, "greet Zorblina")
    assert not unknown.understood and unknown.reply == "Sorry, I don't know anyone called Zorblina."


def test_a_thing_pointed_at_by_a_word_alone_is_not_asked_about_but_handed_over() -> None:
    # "bring me that one": what the speaker shows, which the words do not say (a model may see it)
    kb = scene("mop_1 rdf:type Artifact", 'mop_1 rdfs:label "mop"', "myself sees mop_1")
    for text in ("bring me that one", "pass me that, would you?", "grab this"):
        out = say(kb, text)
        assert not out.understood and out.intent is None, text
    # an object not said at all is still asked for
    assert say(kb, "bring me").clarify
