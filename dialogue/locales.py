"""Locales of a dialogue (chatbot_msgs `locale`, i18n_msgs `GetLocales`): `ll_CC` tags, checked and named.

A dialogue has a locale (given when it starts, or per turn: the detected language of one input).
The offline rules understand English only, so a turn in another language is never read by them
(no English misparse of a French sentence): a hybrid model hands it to its LLM, the rules alone
answer with `__raw_user_input__` carrying the locale. A model is told to reply in the turn's
language (the situation it is given stays in English; intents are language-independent).

>>> normalise_locale("fr-fr"), normalise_locale("en"), language_name("fr_FR"), is_english("en_GB")
('fr_FR', 'en', 'French', True)
"""

from __future__ import annotations

import langcodes

from dialogue.errors import DialogueError

#: The languages the offline rules understand.
RULES_LANGUAGES = ("en",)
#: What `GET /locales` lists for the rules alone (chatbot_msgs locales are `ll_CC`).
RULES_LOCALES = ("en_GB", "en_US")


class LocaleError(DialogueError, ValueError):
    """A locale that is not a language tag (`ll` or `ll_CC`); the message says what is wrong."""


def normalise_locale(locale: str) -> str:
    """`ll_CC` (or `ll`) for a language tag written `ll_CC`, `ll-CC` or `ll`, in any case."""
    text = locale.strip()
    parts = text.replace("-", "_").split("_")
    if not text or len(parts) > 2 or not all(p.isascii() and p.isalpha() for p in parts):
        raise LocaleError(f"locale {locale!r} is not a language tag; write ll or ll_CC, e.g. en_GB or fr_FR")
    try:
        tag = langcodes.Language.get("-".join(parts))
    except (ValueError, langcodes.tag_parser.LanguageTagError):
        tag = None
    country_lost = len(parts) == 2 and tag is not None and tag.territory is None
    if tag is None or not tag.is_valid() or tag.language is None or country_lost:
        raise LocaleError(f"locale {locale!r} names no known language (and country); e.g. en_GB or fr_FR")
    return tag.language if tag.territory is None else f"{tag.language}_{tag.territory}"


def language_of(locale: str | None) -> str:
    """The language part of a locale (None: English, the service's default)."""
    return "en" if not locale else normalise_locale(locale).split("_")[0]


def is_english(locale: str | None) -> bool:
    """True for no locale (the default) and for every English one."""
    return language_of(locale) in RULES_LANGUAGES


def language_name(locale: str) -> str:
    """The language's English name, for the model's prompt ("fr_FR" -> "French")."""
    name: str = langcodes.Language.get(language_of(locale)).language_name("en")
    return name


def supported_locales(*, reads_prompts: bool) -> list[str]:
    """What `GET /locales` answers: the rules' English alone, or any locale (empty) with a model."""
    return [] if reads_prompts else list(RULES_LOCALES)
