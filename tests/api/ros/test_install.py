"""`situated ros install`: refuses with the missing tools named, does nothing on a built prefix, and
vendors the official interface definitions with their licences."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from api.ros import install
from api.ros.install import Installer, RosInstallError, Tool, install_key
from api.ros.prefix import Prefix

INTERFACES = Path(install.__file__).with_name("interfaces")


def test_missing_tools_are_named_with_their_package(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(install, "TOOLS", (Tool("cmake", lambda: False, "cmake"), Tool("make", lambda: True, "make"),
                                           Tool("a C++ compiler (g++)", lambda: False, "g++")))
    with pytest.raises(RosInstallError) as refused:
        Installer(Prefix(tmp_path / "p"), lambda line: None).run()
    assert "cmake, a C++ compiler (g++)" in str(refused.value)
    assert "apt-get install cmake g++" in str(refused.value)
    assert not (tmp_path / "p").exists()  # nothing started


def test_a_prefix_built_from_the_same_inputs_is_left_alone(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = Prefix(tmp_path)
    prefix.stamp.write_text(json.dumps({"key": install_key()}))
    monkeypatch.setattr(install, "TOOLS", (Tool("cmake", lambda: False, "cmake"),))  # would refuse if it ran
    said: list[str] = []
    assert Installer(prefix, said.append).run() is False
    assert "up to date" in said[0]


def test_the_key_follows_every_interface_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    copy = tmp_path / "interfaces"
    import shutil
    shutil.copytree(INTERFACES, copy)
    monkeypatch.setattr(install, "_interfaces", lambda: copy)
    before = install_key()
    (copy / "kb_msgs" / "srv" / "Query.srv").write_text("string[] patterns\n---\nbool success\n")
    assert install_key() != before


@pytest.mark.parametrize("package", install.PACKAGES)
def test_each_vendored_package_keeps_its_licence_and_version(package: str) -> None:
    folder = INTERFACES / package
    licence = (folder / "LICENSE").read_text()
    assert "Apache License" in licence or "Redistribution and use in source and binary forms" in licence
    manifest = (folder / "package.xml").read_text()
    assert f"<name>{package}</name>" in manifest and "<version>0.0.0</version>" not in manifest
    assert package in (INTERFACES / "README.md").read_text()


def test_the_definitions_are_those_the_node_speaks() -> None:
    files = {p.relative_to(INTERFACES).as_posix() for p in INTERFACES.rglob("*") if p.suffix in (".msg", ".srv", ".action")}
    assert {"hri_actions_msgs/msg/Intent.msg", "hri_msgs/msg/LiveSpeech.msg", "hri_msgs/msg/EngagementLevel.msg",
            "chatbot_msgs/msg/DialogueRole.msg", "chatbot_msgs/srv/DialogueInteraction.srv",
            "chatbot_msgs/action/Dialogue.action", "i18n_msgs/srv/GetLocales.srv", "i18n_msgs/action/SetLocale.action",
            "kb_msgs/srv/Query.srv", "kb_msgs/srv/Revise.srv", "kb_msgs/srv/About.srv", "kb_msgs/srv/Lookup.srv",
            "kb_msgs/srv/Manage.srv", "kb_msgs/srv/Sparql.srv", "kb_msgs/srv/Event.srv",
            "kb_msgs/msg/ActiveConcepts.msg"} <= files
