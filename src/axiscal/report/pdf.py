"""The PDF print of the campaign report, typeset with Typst.

Typst installs from the package registry as a Python package that carries its own typesetter (no
system library, no browser), typesets in a fraction of a second and embeds the plots as vector
graphics. The print holds the same sections and numbers as ``report.html``; it is rendered from
its own template (``templates/report/report.typ.j2``) because a page for paper is laid out
differently from a page for a screen.
"""

from __future__ import annotations

import datetime as _dt
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from axiscal.campaign.results import CampaignResults
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_path
from axiscal.io.arguments import check_instance, type_name
from axiscal.report.html import (
    check_compare,
    compare_label,
    decision_statement,
    previous_figures,
    report_facts,
    sections,
    template_environment,
    verdict_rows,
)
from axiscal.report.html import previous_uncertainty
from axiscal.version import __version__

__all__ = ["typst_string", "typst_text", "write_pdf"]


def typst_string(value: Any) -> str:
    """A value as a Typst string literal, for code.

    Parameters
    ----------
    value : object
        Printed with ``str``; None is empty.

    Returns
    -------
    str
        ``"..."`` with quotes and backslashes escaped and newlines as spaces.
    """
    text = "" if value is None else str(value)
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'


def typst_text(value: Any) -> str:
    """A value as text in Typst markup, nothing in it read as markup.

    Parameters
    ----------
    value : object

    Returns
    -------
    str
        ``#"..."``: a string literal placed in markup.

    Examples
    --------
    >>> typst_text("*not bold*")
    '#"*not bold*"'
    """
    return "#" + typst_string(value)


def write_pdf(
    results: CampaignResults, path: str | Path, *, compare: Mapping[str, Any] | None = None, generated: str | None = None,
    certificate_language: str | None = None, dcc: bytes | None = None,
) -> Path:
    """Typeset the report of ``results`` as a PDF.

    Parameters
    ----------
    results : CampaignResults
    path : str or Path
        The PDF to write.
    compare : mapping, keyword-only
        Another campaign's results.json, as for the HTML page.
    generated : str, keyword-only
        When the report was made (default: now, UTC).
    certificate_language : str, keyword-only
        Typeset the calibration certificate in this language (ISO 639-1) instead of the report:
        the certificate layer, its number and "page n of N" on every page, PDF/A-3b, dated by its
        issue date (the same file on every re-run). The campaign must carry the certificate's fields.
    dcc : bytes, keyword-only
        With ``certificate_language``: the DCC, attached to the PDF as ``dcc.xml`` (an associated
        file of relationship Data), so one file holds the certificate for people and for programs.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        When Typst is not installed or fails; for arguments of the wrong kind.
    """
    check_instance("results", results, CampaignResults)
    path = check_path("path", path)
    if compare is not None:
        check_compare(compare)
    if generated is not None and not isinstance(generated, str):
        raise AxiscalError(f"generated must be a str (when the report was made), not {type_name(generated)}")
    try:
        import typst
    except ImportError:  # pragma: no cover - typst is a dependency
        raise AxiscalError("the PDF needs the typst package: pip install typst") from None
    path = Path(path)
    if dcc is not None and certificate_language is None:
        raise AxiscalError("dcc (the attachment) applies only to a certificate: give certificate_language")
    if certificate_language is not None:
        from axiscal.report.certificate import certificate_context, certificate_environment, localised_rows

        env = certificate_environment(certificate_language)
    else:
        env = template_environment()
    env.filters["t"] = typst_text
    env.filters["s"] = typst_string
    with tempfile.TemporaryDirectory(prefix="axiscal-pdf-") as folder:
        root = Path(folder)
        counter = 0
        section_list = sections(results.tests)
        for section in section_list:
            plotted = []
            for test in section["tests"]:
                files = []
                for plot in test.plots:
                    counter += 1
                    name = f"plot{counter}.svg"
                    (root / name).write_text(plot.svg, encoding="utf-8")
                    files.append({"file": name, "title": plot.title})
                plotted.append({"id": test.id, "verdict": test.verdict, "method": test.method, "files": test.files,
                                "table": test.table, "plots": files, "environment": test.environment,
                                "warnings": test.warnings})
            section["tests"] = plotted
        rows = verdict_rows(results, previous_figures(compare), before_uncertainty=previous_uncertainty(compare))
        volumetric = None
        if results.model:
            files = []
            for plot in results.model.get("plots", []):
                counter += 1
                name = f"plot{counter}.svg"
                (root / name).write_text(plot.svg, encoding="utf-8")
                files.append({"file": name, "title": plot.title})
            volumetric = {"method": results.model.get("method", ""), "plots": files}
        extra: dict[str, Any] = {}
        options: dict[str, Any] = {}
        if certificate_language is not None:
            issued = _dt.date.fromisoformat(results.issuer["certificate"]["issue_date"])
            rows = localised_rows(rows, certificate_language)
            extra = {"cert": certificate_context(results, certificate_language),
                     "attach": "dcc.xml" if dcc is not None else None}
            options = {"pdf_standards": "a-3b",
                       "timestamp": _dt.datetime(issued.year, issued.month, issued.day, tzinfo=_dt.timezone.utc)}
            generated = generated or issued.isoformat()
            if dcc is not None:
                (root / "dcc.xml").write_bytes(dcc)
        template = "report/certificate.typ.j2" if certificate_language is not None else "report/report.typ.j2"
        source = env.get_template(template).render(
            **extra,
            version=__version__,
            generated=generated or _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            campaign=results.campaign,
            machine=results.machine,
            facts=report_facts(results),
            verdict=results.verdict,
            verdict_rows=rows,
            has_u_before=any(row["before_U"] for row in rows),
            warnings=results.all_warnings,
            sections=section_list,
            volumetric=volumetric,
            compensation=results.compensation,
            methods=[*sorted({t.method for t in results.tests if t.method}), decision_statement(results.decision_rule)],
            compare={"label": compare_label(compare)} if compare is not None else None,
        )
        main = root / "report.typ"
        main.write_text(source, encoding="utf-8")
        try:
            typst.compile(str(main), output=str(root / "report.pdf"), root=str(root), **options)
        except Exception as exc:  # typst raises its own error types; the message says what failed
            raise AxiscalError(f"typesetting the PDF failed: {' '.join(str(exc).split())[:300]}", path=path) from None
        path.write_bytes((root / "report.pdf").read_bytes())
    return path
