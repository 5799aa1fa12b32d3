"""A word's lemmas by part of speech (lemminflect's English lexicon), looked up once per word.

lemminflect's `getAllLemmas` deep-copies its lexicon's entry on every call (some 25 µs), and a rules
turn asks it about the same few words from several stages (clauses, speech, spelling, references):
five to ten times a turn. The answer depends on the word alone, so it is kept per word, read-only,
for every later turn; the words kept are bounded (what people say to a robot is a small vocabulary;
past the bound, the least recently used word is looked up again).
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
from types import MappingProxyType

from lemminflect import getAllLemmas

#: Words whose lemmas are kept (a few MB at most: each entry is a small dict of short tuples).
KEPT = 8192


@lru_cache(maxsize=KEPT)
def lemmas_of(word: str) -> Mapping[str, tuple[str, ...]]:
    """The word's lemmas by universal part of speech ("went": VERB -> ("go",)), empty when
    lemminflect's lexicon does not know it (read-only: shared by every caller)."""
    return MappingProxyType(getAllLemmas(word))
