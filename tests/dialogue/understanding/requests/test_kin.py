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
     (("wife",), None), (("my", "phone"), None), (("my", "little", "son"), None), (("Tom",), None)],
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
    [(RUTH, "bring my husband his phone", I.BRING_OBJECT, {"object": "phone_1", "recipient": TOM}),
     (TOM, "bring my wife the phone", I.BRING_OBJECT, {"object": "phone_1", "recipient": RUTH}),
     (RUTH, "tell Dad dinner is ready", I.SAY, {"recipient": GEORGE, "object": "dinner is ready"}),
     (AVA, "give the phone to grandpa", I.BRING_OBJECT, {"object": "phone_1", "recipient": GEORGE})],
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


def test_the_answer_to_who_completes_the_request(family: KB) -> None:
    history = [("user", "bring my wife the phone"), ("robot", "Who is your wife?")]
    out = say(family, "Ruth", speaker=NELL, history=history)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "phone_1", "recipient": RUTH})


def test_someone_the_kb_calls_by_the_kin_word_is_called_so(family: KB) -> None:
    family.update(["person_gran rdf:type Human", 'person_gran rdfs:label "grandma"', "myself sees person_gran"])
    out = say(family, "give the phone to grandma", speaker=NELL)
    assert (out.intent, out.roles) == (I.BRING_OBJECT, {"object": "phone_1", "recipient": "person_gran"})
