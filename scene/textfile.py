"""Text scenes: one KB statement per line, ``#`` comments and blank lines ignored (the format of
the evaluation scenes). Loaded as one batch, so a bad line writes nothing."""

from __future__ import annotations

from pathlib import Path

from kb import KB, KbError


def read_statements(path: Path) -> list[str]:
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise KbError(f"cannot read scene file {str(path)!r}: {exc}") from exc
    return [s for line in text.splitlines() if (s := line.strip()) and not s.startswith("#")]


def load_scene(kb: KB, path: Path) -> int:
    """Add the scene's statements to the robot's model; returns how many there were."""
    statements = read_statements(path)
    if statements:
        try:
            kb.update(statements)
        except KbError as exc:
            raise KbError(f"scene {str(path)!r}: {exc}") from exc
    return len(statements)
