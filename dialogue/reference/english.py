"""The one tokeniser, and the helpers that read word lists.

The words themselves are data: closed-class words, prepositions and the grammar's words are in the
language folder (dialogue.understanding.language, `lang/en/`); nouns always come from the KB
(dialogue.reference.lexicon).
"""

from __future__ import annotations

import re
from collections.abc import Sequence

Words = tuple[str, ...]

_TOKEN = re.compile(r"[a-z0-9]+(?:'[a-z]+)?")
#: The same words, and the commas and semicolons that may end a part of a compound request.
_TOKEN_OR_MARK = re.compile(r"[a-z0-9]+(?:'[a-z]+)?|,|;")


def lowered(text: str) -> str:
    """Lower case with typographic apostrophes made plain (the form every tokeniser reads)."""
    return text.lower().replace("\u2019", "'")


def tokens(text: str) -> list[str]:
    """Lower-case whole words; `cup_1` gives `cup 1`, "don't" stays one word."""
    return _TOKEN.findall(lowered(text))


def spans(text: str, marks: bool = False) -> list[tuple[str, int, int]]:
    """Each word (and, with `marks`, each comma or semicolon) with its start and end in `text`.

    The offsets are those of the lowered text, which are the original's whenever lowering kept its
    length (callers that slice the original check that)."""
    pattern = _TOKEN_OR_MARK if marks else _TOKEN
    return [(m.group(), m.start(), m.end()) for m in pattern.finditer(lowered(text))]


def word_set(text: str) -> frozenset[str]:
    return frozenset(text.split())


def phrases(text: str) -> tuple[Words, ...]:
    """ "a b|c" -> (("a", "b"), ("c",)): compact phrase lists."""
    return tuple(tuple(p.split()) for p in text.split("|"))


# -- being moved to the language folder (lang/en/words.toml, prepositions.toml): the grammar's modules
# still read these while they are converted one by one; their values equal the data's.
#: Words that never distinguish a referent.
DETERMINERS = word_set(
    "the a an some any this that these those my your our its one ones please thing there here"
)
PRONOUNS = word_set("it them that this those these")
#: Pronouns that refer to a person only, and those that never do.
PERSONAL = word_set("he she him her himself herself")
NEUTER = word_set("it itself")
#: Possessive determiners whose owner comes from the conversation rather than from the phrase.
POSSESSIVES = word_set("my your our his her their")
#: The speaker, said by the speaker.
ME = word_set("me myself us")
COLOURS = word_set(
    "red green blue yellow orange purple violet pink brown black white grey gray silver gold golden beige "
    "navy turquoise cyan magenta maroon cream tan teal"
)
#: Qualifiers of position, order or size that the KB does not model ("the cup on the left", "the big
#: one"): never a head noun, never evidence for or against a candidate.
POSITIONS = word_set(
    "left right front back behind near nearest closest far farthest furthest big bigger biggest small "
    "smaller smallest large larger largest little other first second third last middle top bottom"
)
#: Nouns naming a part or side of something: "the head of the table", "the far end of the room"
#: name the table and the room.
PARTS = word_set(
    "head end side center centre middle top bottom corner edge front back left right rear part area spot"
)
#: Nouns of what holds food or drink: "the beer cans", "a bottle of water" name the beer and the
#: water when the KB has no such container.
CONTAINERS = word_set(
    "can tin bottle glass cup mug jar box carton packet pack bag bowl pot tub tube crate case"
)
#: General names of furniture and holders whose closed compounds are kinds of them: "the bench"
#: for the "workbench", "the box" for the "toolbox" (not "the board" for the "cupboard").
COMPOUND_HEADS = word_set(
    "bench box chair table shelf shelves cup bag basket bin desk tray rack stand stool cabinet "
    "trolley cart mat lamp light pot jar tin bucket can bowl pan glass"
)
#: Nouns of how much of a thing ("a pair of 3D glasses", "a roll of tape", "a couple of plates"): the
#: phrase names what follows their "of" when the KB has no such thing itself.
MEASURES = word_set("pair couple set piece bunch handful slice bit lot stack pile sheet roll ball reel")
#: Words that make a phrase name several things ("the cereals and the milk", "both cups").
MANY = word_set("and both all every each")

#: Prepositions whose object is where a thing is kept: its support or its zone ("the cup on the table").
SUPPORT_PREPOSITIONS = word_set("on in at inside into onto off from under underneath")
#: Prepositions that say where: after one, a mention is a place ("put it on the shelf" -> "there").
LOCATIVE = (SUPPORT_PREPOSITIONS - word_set("off underneath")) | word_set("near by to")
RELATIVISERS = word_set("that which who whose where")
#: Words that end the core of a noun phrase and start a modifier ("the box *on* the table", "the coke
#: *that* is in the kitchen", "a glass *of* water").
MODIFIER_START = (
    SUPPORT_PREPOSITIONS
    | RELATIVISERS
    | word_set("of near by beside below above behind next close to towards for with without belonging")
    | word_set("between against opposite")
)
#: Titles said in full or short before a name ("mister Kowalski" for "Mr Kowalski", "Dr Adeyemi" for
#: "Doctor Adeyemi"): each group's words stand for one another at the start of a person's name.
TITLES = phrases("mr mister|mrs missus missis|ms miz|dr doctor|prof professor")
#: Number words ("table nine", "take three cups").
NUMBERS = word_set(
    "zero one two three four five six seven eight nine ten eleven twelve thirteen fourteen fifteen "
    "sixteen seventeen eighteen nineteen twenty thirty forty fifty sixty seventy eighty ninety hundred "
    "thousand first second third fourth fifth sixth seventh eighth ninth tenth half dozen"
)
_UNITS = (
    "zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve",
    "thirteen", "fourteen", "fifteen", "sixteen", "seventeen", "eighteen", "nineteen",
)  # fmt: skip
_TENS = ("twenty", "thirty", "forty", "fifty", "sixty", "seventy", "eighty", "ninety")
#: Numbers below a hundred as said in words ("7" -> ("seven",), "21" -> ("twenty", "one")).
SPOKEN_NUMBERS: dict[str, Words] = {
    **{str(n): (w,) for n, w in enumerate(_UNITS)},
    **{str(20 + 10 * t + u): (w, _UNITS[u]) if u else (w,) for t, w in enumerate(_TENS) for u in range(10)},
}
_WRITTEN = {words: digits for digits, words in SPOKEN_NUMBERS.items()}


def other_numbers(words: Sequence[str]) -> Words | None:
    """The words with each number below a hundred written the other way: "plot 7" -> "plot seven",
    "table nine" -> "table 9", "gate twenty one" -> "gate 21"; None when they have no number."""
    out: list[str] = []
    i = 0
    while i < len(words):
        pair, one = tuple(words[i : i + 2]), (words[i],)
        if len(pair) == 2 and pair in _WRITTEN:
            out.append(_WRITTEN[pair])
            i += 2
            continue
        out.extend(SPOKEN_NUMBERS.get(words[i]) or ((_WRITTEN[one],) if one in _WRITTEN else one))
        i += 1
    return tuple(out) if out != list(words) else None


#: Closed-class words in general (pronouns, prepositions, conjunctions, auxiliaries): always words of
#: English, whatever a lexicon of content words says.
FUNCTION_WORDS = NUMBERS | word_set(
    "i you he she it we they me him her us them myself yourself himself herself itself ourselves "
    "themselves mine yours hers ours theirs this that these those who whom whose which what where when "
    "why how if then than because so but and or nor yet while whilst although though unless until since "
    "after before about above across against along among around at behind below beneath beside between "
    "beyond by down during except for from in inside into like near of off on onto out outside over past "
    "through throughout till to toward towards under underneath up upon with within without "
    "am is are was were be been being do does did have has had will would shall should can could may "
    "might must not no yes oh ok okay hey hi hello bye goodbye please thanks"
)
