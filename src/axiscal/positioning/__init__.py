"""Positioning accuracy and repeatability of numerically controlled axes: ISO 230-2 (and VDI/DGQ 3441), test planning, the reader of test runs, the report and the plot."""

from __future__ import annotations

from axiscal.positioning.evaluation import (
    ISO_EDITIONS,
    ISO_SYMBOLS,
    LONG_AXIS_M,
    NO_S_WARNING,
    STANDARDS,
    VDI_SYMBOLS,
    Iso230Result,
    PositioningRun,
    TargetStatistics,
    Vdi3441Result,
    iso230_2,
    iso_edition,
    paper003_table4_run,
    target_statistics,
    vdi3441,
)
from axiscal.positioning.plan import (
    CYCLES,
    PLAN_COLUMNS,
    TARGETS_PER_METRE,
    PositioningTestPlan,
    cycle_csv,
    gcode_program,
    minimum_targets,
    plan_targets,
    plan_test,
    write_plan,
)
from axiscal.positioning.plot import plot_positioning
from axiscal.positioning.report import (
    PositioningEvaluation,
    evaluate_positioning_file,
    render_template,
)
from axiscal.positioning.reader import (
    ALLOWED_UNITS,
    DIRECTIONS,
    ENVIRONMENT_REQUIRED,
    RunFile,
    read_positioning_run,
)

__all__ = [
    "ISO_EDITIONS",
    "LONG_AXIS_M",
    "NO_S_WARNING",
    "PositioningRun",
    "TargetStatistics",
    "Iso230Result",
    "ISO_SYMBOLS",
    "VDI_SYMBOLS",
    "Vdi3441Result",
    "target_statistics",
    "iso230_2",
    "vdi3441",
    "STANDARDS",
    "iso_edition",
    "paper003_table4_run",
    "DIRECTIONS",
    "ENVIRONMENT_REQUIRED",
    "ALLOWED_UNITS",
    "RunFile",
    "read_positioning_run",
    "CYCLES",
    "PLAN_COLUMNS",
    "TARGETS_PER_METRE",
    "PositioningTestPlan",
    "minimum_targets",
    "plan_targets",
    "plan_test",
    "cycle_csv",
    "gcode_program",
    "write_plan",
    "plot_positioning",
    "PositioningEvaluation",
    "evaluate_positioning_file",
    "render_template",
]
