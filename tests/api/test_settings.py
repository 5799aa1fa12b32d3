"""Settings precedence: defaults < config file < SITUATED_* env < explicit values."""

from __future__ import annotations

from pathlib import Path

import pytest

from api.settings import Settings, SettingsError, load_settings


def test_defaults_are_safe() -> None:
    settings = Settings()
    assert settings.host == "127.0.0.1" and settings.port == 8000
    assert settings.llm == "rules" and settings.token is None and settings.cors_origins == []
    assert settings.sparql_update is False and settings.allow_anonymous_reads is True


def test_file_env_and_overrides(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    config = tmp_path / "situated.toml"
    config.write_text('port = 9000\nllm = "ollama:gemma3:1b"\n'
                      '[limits]\nmax_statements = 5\nmax_patterns = 7\n')
    from_file = load_settings(config)
    assert (from_file.port, from_file.llm, from_file.limits.max_statements) == (9000, "ollama:gemma3:1b", 5)
    monkeypatch.setenv("SITUATED_PORT", "9100")
    monkeypatch.setenv("SITUATED_LIMITS__MAX_STATEMENTS", "6")
    monkeypatch.setenv("SITUATED_TOKEN", "abc")
    merged = load_settings(config, port=9200, llm=None)
    assert merged.port == 9200  # explicit beats env beats file
    assert merged.limits.max_statements == 6 and merged.limits.max_patterns == 7  # nested merge
    assert merged.llm == "ollama:gemma3:1b"  # None overrides are ignored
    assert merged.token is not None and merged.token.get_secret_value() == "abc"


def test_json_config_via_env(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    config = tmp_path / "situated.json"
    config.write_text('{"cors_origins": ["http://viewer.local"], "sparql_update": true}')
    monkeypatch.setenv("SITUATED_CONFIG", str(config))
    settings = load_settings()
    assert settings.cors_origins == ["http://viewer.local"] and settings.sparql_update


@pytest.mark.parametrize(("name", "text", "message"), [
    ("bad.toml", "port = [", "not valid"),
    ("bad.yaml", "port: 1", "must end in .toml or .json"),
    ("bad.json", '{"port": "high"}', "port"),
    ("bad2.json", '{"colour": 1}', "colour"),
    ("bad3.json", '{"cors_origins": ["*"]}', "wildcard"),
])
def test_bad_config_is_a_clear_error(tmp_path: Path, name: str, text: str, message: str) -> None:
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(SettingsError, match=message):
        load_settings(path)


def test_missing_config_file(tmp_path: Path) -> None:
    with pytest.raises(SettingsError, match="cannot read config file"):
        load_settings(tmp_path / "nope.toml")


def test_the_role_follows_store_and_writer_url(tmp_path: Path) -> None:
    assert Settings().role == "standalone"
    assert Settings(store="sparql+http://127.0.0.1:7878").role == "writer"
    reader = Settings(store="sparql+http://127.0.0.1:7878", writer_url="http://127.0.0.1:8000/")
    assert reader.role == "reader" and reader.writer_url == "http://127.0.0.1:8000"
    with pytest.raises(SettingsError, match="writer_url needs store"):
        load_settings(writer_url="http://127.0.0.1:8000")
    with pytest.raises(SettingsError, match=r"a reader .* keeps none"):
        load_settings(store="sparql+http://h:1", writer_url="http://127.0.0.1:8000", data_dir=tmp_path)
    with pytest.raises(SettingsError, match="writer_url must be"):
        load_settings(store="sparql+http://h:1", writer_url="ftp://x")
    with pytest.raises(SettingsError, match="must look like sparql"):
        load_settings(store="http://127.0.0.1:7878")


def test_the_store_timeout_is_bounded_and_shorter_than_the_turn_deadline() -> None:
    """A stalled store must not hold a dialogue turn past its deadline (issue 19, item 13)."""
    default = load_settings(store="sparql+http://h:1")
    assert 0 < default.store_timeout < default.deadline
    assert load_settings(store="sparql+http://h:1", store_timeout=0.5, deadline=1).store_timeout == 0.5
    with pytest.raises(SettingsError, match=r"store_timeout \(5 s\) must be shorter than deadline \(5 s\)"):
        load_settings(store="sparql+http://h:1", store_timeout=5, deadline=5)
    with pytest.raises(SettingsError, match="store_timeout"):
        load_settings(store="sparql+http://h:1", store_timeout=0)
