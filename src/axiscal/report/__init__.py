"""Reports: the campaign's HTML page (and its PDF print), rendered from templates shipped with axiscal."""

from __future__ import annotations

from axiscal.report.html import format_number, render_html, template_environment
from axiscal.report.writer import ReportFiles, report_campaign, write_report

__all__ = ["format_number", "render_html", "template_environment", "ReportFiles", "report_campaign", "write_report"]
