"""Reports: the campaign's HTML page and its PDF print, the calibration certificate and its Digital
Calibration Certificate (DCC), and the demo job on the built-in example, rendered from templates
shipped with axiscal."""

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
from axiscal.report.certificate import (
    COVERAGE_FACTOR,
    COVERAGE_PROBABILITY,
    certificate_context,
    certificate_environment,
    check_certificate,
    figure_rows,
    localised_rows,
    missing_certificate_fields,
    render_certificate_html,
)
from axiscal.report.cycle import CycleResult, CycleSettings, closed_cycle
from axiscal.report.dcc import DCC_NS, SCHEMA_VERSION, SI_NS, dcc_summary, dcc_xml, dsi_unit, read_dcc
from axiscal.report.dcc_sign import PARTS_NS, Verification, sign_dcc, verify_dcc
from axiscal.report.history import history_section
from axiscal.report.html import (
    compare_label,
    decision_statement,
    display_unit,
    format_number,
    page_context,
    previous_figures,
    previous_uncertainty,
    render_html,
    report_facts,
    sections,
    template_environment,
    verdict_rows,
)
from axiscal.report.i18n import DOMAIN, catalog_path, format_date_for, format_decimal_for, translations
from axiscal.report.pdf import (
    typst_string,
    typst_text,
    write_pdf,
)
from axiscal.report.writer import (
    ReportFiles,
    read_compared,
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
    "page_context",
    "read_compared",
    "COVERAGE_FACTOR",
    "COVERAGE_PROBABILITY",
    "certificate_context",
    "certificate_environment",
    "check_certificate",
    "figure_rows",
    "localised_rows",
    "missing_certificate_fields",
    "render_certificate_html",
    "DCC_NS",
    "SI_NS",
    "SCHEMA_VERSION",
    "dcc_summary",
    "dcc_xml",
    "dsi_unit",
    "read_dcc",
    "PARTS_NS",
    "Verification",
    "sign_dcc",
    "verify_dcc",
    "DOMAIN",
    "catalog_path",
    "format_date_for",
    "format_decimal_for",
    "translations",
]
