"""The speaker's family said by kin words, through the family relations the KB holds."""

import pytest

from dialogue import intents as I
from dialogue.understanding.requests.kin import kin_word, relatives
from kb import KB
from tests.dialogue.conftest import english, lexicon_of, scene_kb
from tests.dialogue.understanding.test_interpret import say

RUTH, TOM, AVA, GEORGE, NELL = "person_ruth", "person_tom", "person_ava", "person_george", "person_nell"


@pytest.fixture
def family() -> KB:
    people = [s for p, name in ((RUTH, "Ruth"), (TOM, "Tom"), (AVA, "Ava"), (GEORGE, "George"), (NELL, "Nell"))
              for s in (f"{p} rdf:type Human", f'{p} rdfs:label "{name}"', f"myself sees {p}")]  # fmt: skip
    return scene_kb(
        None, "myself rdf:type Robot", *people,
        f"{RUTH} isSpouseOf {TOM}", f"{TOM} hasChild {AVA}", f"{AVA} isChildOf {RUTH}",
        f"{GEORGE} isParentOf {RUTH}",
        "phone_1 rdf:type Artifact", 'phone_1 rdfs:label "phone"', f"phone_1 belongsTo {TOM}", "myself sees phone_1",
    )  # fmt: skip


@pytest.mark.parametrize(
    ("words", "word"),
    [(("my", "wife"), "wife"), (("our", "youngest"), "youngest"), (("Dad",), "dad"), (("grandma",), "grandma"),
     (("wife",), None), (("my", "phone"), None), (("my", "little", "son"), None), (("Tom",), None),
     (("the", "dad"), None), (("a", "mum"), None), (("that", "sister"), None), (("this", "grandma"), None),
     (("my", "dad"), "dad"), (("my", "spouse"), "spouse")],
)  # fmt: skip
def test_a_kin_phrase_is_the_speakers_kin_word(words: tuple[str, ...], word: str | None) -> None:
    assert kin_word(english(), words) == word


def test_relatives_follow_every_spelling_either_way_round(family: KB) -> None:
    snapshot = lexicon_of(family).snapshot
    assert relatives(english(), snapshot, TOM, "wife") == [RUTH]  # (said by Ruth's property)
    assert relatives(english(), snapshot, RUTH, "husband") == [TOM]
    assert relatives(english(), snapshot, RUTH, "daughter") == [AVA]  # (Ava isChildOf Ruth)
    assert relatives(english(), snapshot, AVA, "mum") == [RUTH, TOM]  # no gender in the KB: both
    assert relatives(english(), snapshot, AVA, "grandpa") == [GEORGE]
    assert relatives(english(), snapshot, NELL, "wife") == []


@pytest.mark.parametrize(
    ("speaker", "text", "intent", "roles"),
    [(RUTH, "bring my spouse his phone", I.BRING_OBJECT, {"object": "phone_1", "recipient": TOM}),
     (TOM, "give the phone to my youngest", I.BRING_OBJECT, {"object": "phone_1", "recipient": AVA}),
     (AVA, "give the phone to my grandparent", I.BRING_OBJECT, {"object": "phone_1", "recipient": GEORGE})],
)  # fmt: skip
def test_a_kin_word_is_whom_the_kb_relates_to_the_speaker(
    family: KB, speaker: str, text: str, intent: str, roles: dict[str, str]
) -> None:
    out = say(family, text, speaker=speaker)
    assert (out.intent, out.roles) == (intent, roles)


@pytest.mark.parametrize(("speaker", "text"), [(NELL, "bring my wife her phone"), (AVA, "tell mum tea is ready")])
def test_whom_the_kb_does_not_say_or_says_several_of_is_asked(family: KB, speaker: str, text: str) -> None:
    out = say(family, text, speaker=speaker)
    assert out.intent is None and out.clarify and out.open_role == "recipient" and out.reply.startswith("Who is your")


@pytest.mark.parametrize(
    ("speaker", "text", "asked"),
    [(RUTH, "bring my husband his phone", "Who is your husband?"), (TOM, "bring my wife the phone", "Who is your wife?"),
     (RUTH, "tell Dad dinner is ready", "Who is your dad?"), (AVA, "give the phone to grandpa", "Who is your grandpa?")],
)  # fmt: skip
def test_a_gendered_kin_word_the_kb_gives_no_gender_for_is_asked(family: KB, speaker: str, text: str, asked: str) -> None:
    out = say(family, text, speaker=speaker)
    assert out.intent is None and out.clarify and out.open_role == "recipient" and out.reply == asked


@pytest.mark.parametrize(
    ("facts", "text", "asked"),
    [(["person_tom isParentOf person_priya"], "take my mum the charger", "Who is your mum?"),
     (["person_tom hasSibling person_priya"], "bring my sister the charger", "Who is your sister?")],
)  # fmt: skip
def test_a_lone_relative_is_not_taken_for_the_other_gender(facts: list[str], text: str, asked: str) -> None:
    kb = scene_kb(
        None, "myself rdf:type Robot", "charger_1 rdf:type Artifact", 'charger_1 rdfs:label "charger"',
        "myself sees charger_1", *facts,
        *(s for p, name in (("person_tom", "Tom"), ("person_priya", "Priya"))
          for s in (f"{p} rdf:type Human", f'{p} rdfs:label "{name}"', f"myself sees {p}")),
    )  # fmt: skip
    out = say(kb, text, speaker="person_priya")
    assert out.intent is None and out.clarify and out.reply == asked


def test_a_relative_called_by_the_kin_word_is_meant(family: KB) -> None:
    family.update([f'{GEORGE} rdfs:label "Dad"'])
    out = say(family, "tell my dad dinner is ready", speaker=RUTH)
    assert (out.intent, out.roles) == (I.SAY, {"recipient": GEORGE, "object": "dinner is ready"})


@pytest.mark.parametrize("speaker", [RUTH, AVA])
def test_a_kin_word_after_a_determiner_is_not_the_speakers_relative(family: KB, speaker: str) -> None:
    out = say(family, "bring the dad the phone", speaker=speaker)  # (Ruth's one parent, Ava's two)
    assert out.intent is None and not out.reply.startswith("Who is your")


def test_the_answer_to_who_completes_the_request(family: KB) -> None:
    history = [("user", "bring my wife the phone"), ("robot", "Who is your wife?")]
    out = say(family, "Ruth", speaker=NELL, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "phone_1", "recipient": RUTH})


def test_someone_the_kb_calls_by_the_kin_word_is_called_so(family: KB) -> None:
    family.update(["person_gran rdf:type Human", 'person_gran rdfs:label "grandma"', "myself sees person_gran"])
    out = say(family, "give the phone to grandma", speaker=NELL)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "phone_1", "recipient": "person_gran"})
