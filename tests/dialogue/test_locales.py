"""Locale tags: checked, normalised to ll_CC, named; English or not."""

from __future__ import annotations

import pytest

from dialogue.locales import LocaleError, is_english, language_name, normalise_locale, supported_locales


@pytest.mark.parametrize(("given", "expected"), [("fr_FR", "fr_FR"), ("fr-fr", "fr_FR"), ("EN", "en"),
                                                 ("ca_ES", "ca_ES"), (" en_GB ", "en_GB")])
def test_normalised(given: str, expected: str) -> None:
    assert normalise_locale(given) == expected


@pytest.mark.parametrize("bad", ["", "french", "xx", "fr_FRA", "en_GB_x", "f1_FR", "zh_Hant_TW"])
def test_refused_saying_why(bad: str) -> None:
    with pytest.raises(LocaleError, match=r"e\.g\. en_GB or fr_FR"):
        normalise_locale(bad)


def test_english_and_names() -> None:
    assert is_english(None) and is_english("en_US") and not is_english("fr_FR")
    assert language_name("ca_ES") == "Catalan" and language_name("de") == "German"
    assert supported_locales(reads_prompts=False) == ["en_GB", "en_US"] and supported_locales(reads_prompts=True) == []
