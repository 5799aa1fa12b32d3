"""What users import: each package's ``__all__`` names real objects, and the KB backends share one API."""

from __future__ import annotations

import importlib
import inspect

import pytest

import dialogue
import kb
from kb import KB, Facade, KbError, KnowledgeBase, RemoteKB


@pytest.mark.parametrize("package", ["kb", "dialogue"])
def test_every_name_of_all_is_importable(package: str) -> None:
    module = importlib.import_module(package)
    missing = [name for name in module.__all__ if not hasattr(module, name)]
    assert missing == []
    assert len(set(module.__all__)) == len(module.__all__)


def test_kb_exports_the_backends_the_protocol_and_every_error() -> None:
    assert {"KB", "RemoteKB", "KnowledgeBase", "KbError"} <= set(kb.__all__)
    errors = {name for name, value in vars(importlib.import_module("kb.errors")).items()
              if inspect.isclass(value) and issubclass(value, KbError)}
    assert errors <= set(kb.__all__)


def test_dialogue_exports_engine_config_result_and_models() -> None:
    assert {"DialogueEngine", "EngineConfig", "TurnResult", "DialogueManager", "ChatModel",
            "DialogueError", "parse_spec"} <= set(dialogue.__all__)


def test_both_backends_are_the_one_facade_and_satisfy_the_protocol() -> None:
    assert issubclass(KB, Facade) and issubclass(RemoteKB, Facade)
    with KB(ontology=False) as local:
        assert isinstance(local, KnowledgeBase)


def test_the_backends_only_implement_primitives() -> None:
    """Argument checking lives once, in the facade: neither backend redefines a public call of it."""
    public = {name for name in vars(Facade) if not name.startswith("_")}
    for backend in (KB, RemoteKB):
        redefined = public & {name for name in vars(backend) if not name.startswith("_")}
        assert redefined <= {"revision", "lock", "models", "summary", "close", "unsubscribe"}, backend


def test_every_dialogue_error_has_the_one_root() -> None:
    from dialogue.evaluation.cases import EvalError
    from dialogue.intents import IntentError
    from dialogue.llm.base import ModelError
    from dialogue.llm.spec import SpecError
    from dialogue.prompts import PromptError
    from dialogue.schema import AnswerError
    from dialogue.sessions.store import StateError

    for error in (EvalError, IntentError, ModelError, SpecError, PromptError, AnswerError, StateError,
                  dialogue.SessionError):
        assert issubclass(error, dialogue.DialogueError), error
