"""The lexicons of the last few snapshots, shared by the turns of an engine: a lexicon is made once
per snapshot, from the latest of an earlier revision (`Lexicon` updates it by what changed)."""

from __future__ import annotations

import threading

from dialogue.reference.grounding import Snapshot
from dialogue.reference.lexicon import Lexicon, phrase, singular
from dialogue.reference.synonyms import synonyms
from dialogue.understanding.language import Language


class LexiconCache:
    """The lexicons of the last few snapshots (snapshots are immutable, so this is safe to share):
    a turn that holds a snapshot a little older than the latest still finds its lexicon."""

    def __init__(self, lang: Language) -> None:
        self.lang = lang
        self._lock = threading.Lock()
        self._build = threading.Lock()
        self._recent: list[Lexicon] = []  # oldest first
        # The lemma tables and the synonyms file load on first use (a few hundred ms): here, when
        # an engine is made, rather than inside its first turn's deadline.
        singular("cups")
        synonyms(lang, phrase)

    def made(self, snapshot: Snapshot) -> Lexicon | None:
        """The lexicon of ``snapshot`` if it is made already (cheap: callable on an event loop)."""
        with self._lock:
            recent = self._recent
        return next((lex for lex in reversed(recent) if lex.snapshot is snapshot), None)

    def get(self, snapshot: Snapshot) -> Lexicon:
        found = self.made(snapshot)
        if found is not None:
            return found
        with self._build:  # one at a time: a turn that needs the lexicon the worker makes waits for it
            found = self.made(snapshot)
            if found is not None:
                return found
            with self._lock:
                recent = self._recent
            # updated from the latest lexicon of an earlier revision (a later one cannot say what
            # changed since: it would be rebuilt)
            earlier = [lex for lex in recent if lex.snapshot.revision <= snapshot.revision]
            lex = Lexicon(snapshot, self.lang, earlier[-1] if earlier else (recent[-1] if recent else None))
            with self._lock:
                self._recent = sorted([*recent, lex], key=lambda x: x.snapshot.revision)[-_RECENT:]
            return lex


#: Lexicons a cache keeps.
_RECENT = 3
