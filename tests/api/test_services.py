"""Start-up and shutdown: scene, extra ontology files, the data-dir snapshot, bad settings."""

from __future__ import annotations

import asyncio
from pathlib import Path

import pytest

from api.services import start_services
from api.settings import Settings, SettingsError
from dialogue.llm.openai import OpenAIModel
from kb import KbError
from tests.api.conftest import SCENE
from tests.waiting import until


def test_data_dir_journal_survives_a_restart(tmp_path: Path) -> None:
    settings = Settings(data_dir=tmp_path / "data")
    first = start_services(settings)
    first.kb.update(["cup_7 isOn table_1"])
    first.kb.update(["x believes y"], ["alice"])
    assert (tmp_path / "data" / "journal.log").stat().st_size > 0  # written before the update returned
    first.stop()
    assert (tmp_path / "data" / "snapshot.json").exists()  # a clean stop compacts
    second = start_services(settings)
    try:
        assert second.kb.find(["cup_7 isOn ?t"]) == [{"t": "table_1"}]
        assert second.kb.find(["x believes ?o"], models=["alice"]) == [{"o": "y"}]
    finally:
        second.stop()


def test_extra_ontology_and_scene(tmp_path: Path) -> None:
    extra = tmp_path / "extra.ttl"
    extra.write_text("@prefix : <http://kb.openrobots.org#> .\n"
                     "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n"
                     ":Mug rdfs:subClassOf :Artifact .\n")
    services = start_services(Settings(ontology_files=[extra], scene=SCENE))
    try:
        services.kb.update(["mug_1 rdf:type Mug"])
        assert "Artifact" in services.kb.classesof("mug_1")
        assert services.kb.find(["myself sees cup_1"]) == ["myself sees cup_1"]
    finally:
        services.stop()


def test_bad_scene_and_bad_backend_are_clear_errors(tmp_path: Path) -> None:
    bad = tmp_path / "bad.txt"
    bad.write_text("cup_1 isOn table_1\nthis is not a statement at all\n")
    with pytest.raises(KbError, match=r"bad\.txt"):
        start_services(Settings(scene=bad))
    with pytest.raises(KbError, match="cannot read scene file"):
        start_services(Settings(scene=tmp_path / "missing.txt"))
    with pytest.raises(SettingsError, match="llm"):
        start_services(Settings(llm="nonsense"))


def test_aclose_closes_the_model_it_built_and_not_one_it_was_given() -> None:
    built = start_services(Settings(scene="none", llm="hybrid:openai:m@http://127.0.0.1:9/v1"))
    given_model = OpenAIModel("m", "http://127.0.0.1:9/v1")
    given = start_services(Settings(scene="none"), model=given_model)
    inner = built.model.llm
    assert isinstance(inner, OpenAIModel) and built.owns_model and not given.owns_model

    async def use_then_stop() -> None:
        for model in (inner, given_model):
            model.client.get()  # as a turn does
        await built.aclose()
        await given.aclose()

    asyncio.run(use_then_stop())
    assert not inner.client.open and given_model.client.open


def test_the_first_snapshot_is_built_at_start_and_followed_after(tmp_path: Path) -> None:
    services = start_services(Settings(scene=SCENE))
    try:
        engine = services.dialogues.engine
        kb = services.kb
        # Built by the grounding's worker as the service starts: no turn has run, nobody asked.
        until(lambda: engine.grounder.cached(kb.revision) is not None)
        kb.update(["cup_9 rdf:type dbr:Cup", "myself sees cup_9"])
        until(lambda: engine.grounder.cached(kb.revision) is not None)
        snapshot = engine.grounder.cached(kb.revision)
        assert snapshot is not None and snapshot.get("cup_9") is not None
        assert snapshot.changed  # taken up from the commit, not rebuilt
    finally:
        services.stop()
