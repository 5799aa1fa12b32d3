"""Questions about what the robot was asked: "what did I ask you for?" is answered from the
conversation (the speaker's latest turns but recall questions read again in the conversation each
was said in, the requests among them said back); "what's left?", "what were you doing?" ask what the
service does not keep (which tasks are done is the robot's, not the dialogue's), and the answer says
so."""

from __future__ import annotations

from dialogue import intents as I
from dialogue.reference.english import Words
from dialogue.understanding.context import Reader
from dialogue.understanding.followups.proposal import action_said
from dialogue.understanding.language import Language
from dialogue.understanding.outcome import Outcome
from dialogue.understanding.parsed import Parse
from dialogue.understanding.replies import say
from dialogue.understanding.said import Said
from dialogue.understanding.speech.plain import strip_politeness
from dialogue.understanding.speech.repair import normalise, strip_vocative

#: The requests said back at most, the latest.
MAX_RECALLED = 3
#: The speaker's earlier turns read again at most, the latest: each is a whole interpretation, and
#: the answer says back only the last few requests anyway.
MAX_READ = 12
#: Intents that ask nothing of the robot worth saying back.
_NOT_ASKED = frozenset({I.GREET, I.RAW_USER_INPUT})


class _Words:
    """The language's questions about what was asked (`questions.toml` [situation])."""

    def __init__(self, lang: Language) -> None:
        said = lang.questions.situation
        self.asked_for, self.untracked, self.tail = said.asked_for, said.untracked, said.recall_tail


def recalled(lang: Language, w: Words) -> Parse | None:
    """The question "what did I ask you for?" ("asked_for") or "what's left?" ("untracked"), said
    whole (maybe with "then", "again"...), or None."""
    q = lang.derived(_Words)
    while len(w) > 1 and w[-1] in q.tail:
        w = w[:-1]
    if w in q.asked_for:
        return Parse("question", question="asked_for", words=w)
    if w in q.untracked:
        return Parse("question", question="untracked", words=w)
    return None


def asked_for(r: Reader) -> Outcome:
    """What the speaker asked the robot to do in this conversation, the latest few, in order."""
    lang = r.lexicon.lang
    actions: list[str] = []
    last: tuple[object, ...] = ()
    # (a recall question read again would recall the shorter conversation: twice the work each time)
    turns = [i for i, u in enumerate(r.history) if u.speaker == r.speaker and not _recalls(r, u.text)]
    for i in turns[-MAX_READ:]:
        again = r.within(r.history[:i]).interpret(r.history[i].text)
        if again.intent is None or again.intent in _NOT_ASKED:
            continue
        read = tuple((o.intent, sorted(o.roles.items())) for o in again.steps())
        if read != last:  # ("yes" to "Shall I bring the pear to Bo?" is that request, said once)
            actions.append(action_said(lang, again.reply))
        last = read
    if not actions:
        return Outcome(say(lang, "recall.nothing_asked"))
    latest = actions[-MAX_RECALLED:]
    said = latest[0]
    for action in latest[1:]:
        said = say(lang, "confirm.then", action=said, next=action)
    return Outcome(say(lang, "recall.asked", actions=said))


def _recalls(r: Reader, text: str) -> bool:
    """Whether the words, said whole, ask what was asked or what is left (as the grammar reads them:
    without politeness or the robot's name)."""
    lang = r.lexicon.lang
    words = strip_politeness(lang, normalise(lang, Said.read(lang, text)), r.robot_name)
    return recalled(lang, tuple(strip_vocative(lang, words, r.robot_name))) is not None


def untracked(r: Reader) -> Outcome:
    """What the service does not keep: which tasks are done, what the robot is doing."""
    return Outcome(say(r.lexicon.lang, "recall.untracked"))
