"""Reports: the campaign's HTML page and its PDF print, and the demo job on the built-in example,
rendered from templates shipped with axiscal."""

from __future__ import annotations

from axiscal.report.demo import (
    DEMO_AXES,
    DEMO_FILES,
    DemoResult,
    builtin_example,
    run_demo,
    write_as_found_campaign,
    write_as_left_campaign,
)
from axiscal.report.cycle import CycleResult, CycleSettings, closed_cycle
from axiscal.report.history import history_section
from axiscal.report.html import (
    compare_label,
    decision_statement,
    display_unit,
    format_number,
    previous_figures,
    previous_uncertainty,
    render_html,
    report_facts,
    sections,
    template_environment,
    verdict_rows,
)
from axiscal.report.pdf import (
    typst_string,
    typst_text,
    write_pdf,
)
from axiscal.report.writer import (
    ReportFiles,
    report_campaign,
    write_report,
)

__all__ = [
    "CycleResult",
    "CycleSettings",
    "closed_cycle",
    "history_section",
    "decision_statement",
    "template_environment",
    "render_html",
    "display_unit",
    "format_number",
    "previous_figures",
    "previous_uncertainty",
    "compare_label",
    "verdict_rows",
    "report_facts",
    "sections",
    "ReportFiles",
    "write_report",
    "report_campaign",
    "typst_string",
    "typst_text",
    "write_pdf",
    "DEMO_AXES",
    "DEMO_FILES",
    "DemoResult",
    "write_as_found_campaign",
    "write_as_left_campaign",
    "builtin_example",
    "run_demo",
]
