"""Electronic levels: the straightness profile and the angular error motion from level readings (ISO 230-1)."""

from __future__ import annotations

from axiscal.levels.files import ANGLE_COLUMNS, LevelEvaluation, LevelRun, evaluate_levels, read_level_run
from axiscal.levels.plot import plot_levels
from axiscal.levels.profile import INTEGRATIONS, LevelProfile, level_profile

__all__ = [
    "INTEGRATIONS",
    "LevelProfile",
    "level_profile",
    "ANGLE_COLUMNS",
    "LevelRun",
    "read_level_run",
    "LevelEvaluation",
    "evaluate_levels",
    "plot_levels",
]
