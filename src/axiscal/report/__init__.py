"""Reports: the campaign's HTML page and its PDF print, and the demo job on the built-in example,
rendered from templates shipped with axiscal."""

from __future__ import annotations

from axiscal.report.demo import DEMO_FILES, DemoResult, builtin_example, run_demo
from axiscal.report.html import format_number, render_html, template_environment
from axiscal.report.writer import ReportFiles, report_campaign, write_report

__all__ = [
    "DEMO_FILES",
    "DemoResult",
    "builtin_example",
    "run_demo",
    "format_number",
    "render_html",
    "template_environment",
    "ReportFiles",
    "report_campaign",
    "write_report",
]
