"""The ask role's form and scene (tests/dialogue/ask/conftest.py), for the reader of its answers."""

from tests.dialogue.ask.conftest import form, lexicon

__all__ = ["form", "lexicon"]
