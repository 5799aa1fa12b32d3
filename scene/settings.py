"""The scene's settings: part of the service settings (``scene_settings``), owned by the scene package."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, Field


class SceneSettings(BaseModel):
    """The scene's policies (scene-compat S5, S7, S8; defaults as the simulator) and engagement."""

    fov_degrees: float = Field(default=120.0, gt=0, le=360, description="field of view of every agent")
    range_m: float = Field(default=3.5, gt=0, description="how far agents see, metres")
    agents_in_zones: bool = Field(default=False, description="state `<agent> isIn <zone>` (off upstream)")
    zones: Literal["all", "largest"] = Field(default="all", description="zones of a straddling item")
    supports: Literal["all", "top"] = Field(default="all", description="isOn every item below, or the top")
    engagement_hz: float = Field(default=10.0, ge=0, le=100, description="engagement ticks per second")
