"""Writing a campaign's report folder in one step: report.html, results.json, compensation files, PDF.

The folder is built next to its destination and swapped into place whole at the end
(:func:`~axiscal.io.folders.atomic_folder`), so a failed or killed run never leaves a half-written
report, and an earlier report stays as it was until the new one is complete.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from axiscal.campaign.config import Campaign, TestSpec, read_campaign
from axiscal.campaign.results import CampaignResults, results_payload
from axiscal.campaign.runner import run_campaign
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_mapping, check_path
from axiscal.io.folders import atomic_folder
from axiscal.io.jsonio import dumps, read_json
from axiscal.report.html import check_compare, render_html

__all__ = ["ReportFiles", "write_report", "report_campaign", "read_compared"]


@dataclass(frozen=True)
class ReportFiles:
    """Where a campaign's report was written.

    Attributes
    ----------
    folder : Path
        The report folder.
    html, results : Path
        ``report.html`` and ``results.json``.
    pdf : Path or None
        ``report.pdf`` when asked for.
    certificate : tuple of Path
        With a certificate: ``certificate.html`` and ``certificate.pdf`` (PDF/A-3b, the DCC attached).
    dcc : Path or None
        ``dcc.xml``, the Digital Calibration Certificate, when asked for (and with a certificate).
    compensation : tuple of Path
        The compensation files.
    results_data : CampaignResults
        The results the files were made from.
    history : dict or None
        With ``history=True``: the history section, with ``campaign_id``, ``database`` (where the
        campaign was stored), ``machine`` and ``campaigns``.
    """

    folder: Path
    html: Path
    results: Path
    pdf: Path | None
    compensation: tuple[Path, ...]
    results_data: CampaignResults
    history: Mapping[str, Any] | None = None
    certificate: tuple[Path, ...] = ()
    dcc: Path | None = None


def write_report(
    results: CampaignResults,
    out_dir: str | Path,
    *,
    compare: Mapping[str, Any] | None = None,
    pdf: bool = False,
    extra_files: Mapping[str, str] | None = None,
    history: Mapping[str, Any] | None = None,
    certificate: bool = False,
    dcc: bool = False,
) -> ReportFiles:
    """Write the report folder of ``results`` atomically.

    Parameters
    ----------
    results : CampaignResults
    out_dir : str or Path
        The report folder; replaced as a whole when it exists.
    compare : mapping, keyword-only
        Another campaign's results.json, shown beside each figure.
    pdf : bool, keyword-only
        Also write ``report.pdf``.
    extra_files : mapping, keyword-only
        Relative path -> text of further files (the compensation tables).
    history : mapping, keyword-only
        The history section (:func:`~axiscal.report.history.history_section`).
    certificate : bool, keyword-only
        Also write the calibration certificate (:mod:`axiscal.report.certificate`) in its main
        language: ``certificate.html``, ``certificate.pdf`` (PDF/A-3b with the DCC attached) and
        ``dcc.xml``.
    dcc : bool, keyword-only
        Also write ``dcc.xml``, the Digital Calibration Certificate (:mod:`axiscal.report.dcc`).

    Returns
    -------
    ReportFiles

    Raises
    ------
    AxiscalError
        When the folder cannot be written; nothing is left half-written. For arguments of the
        wrong kind, or an extra file whose name leaves the folder. With ``certificate`` or
        ``dcc``: for a campaign that lacks a certificate's fields (one line listing them all;
        nothing is written).
    """
    check_instance("results", results, CampaignResults)
    out_dir = check_path("out_dir", out_dir)
    if compare is not None:
        check_compare(compare)
    check_instance("pdf", pdf, bool)
    check_instance("certificate", certificate, bool)
    check_instance("dcc", dcc, bool)
    if certificate or dcc:
        from axiscal.report.certificate import check_certificate

        check_certificate(results)
    if extra_files is not None:
        check_mapping("extra_files", extra_files, what="a mapping of relative file names to texts")
        for name, text in extra_files.items():
            if not isinstance(name, str) or not name or Path(name).is_absolute() or ".." in Path(name).parts:
                raise AxiscalError(f"extra_files: {name!r} must be a file name relative to the report folder")
            if not isinstance(text, str):
                raise AxiscalError(f"extra_files['{name}'] must be the file's text (a str), not {type(text).__name__}")
    def fill(staging: Path) -> tuple[list[Path], Path | None]:
        html = render_html(results, compare=compare, history=history)
        (staging / "report.html").write_text(html, encoding="utf-8")
        (staging / "results.json").write_text(dumps(results_payload(results)), encoding="utf-8")
        written = []
        for name, text in (extra_files or {}).items():
            target = staging / name
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(text, encoding="utf-8")
            written.append(out_dir / name)
        pdf_path = None
        if pdf:
            from axiscal.report.pdf import write_pdf

            write_pdf(results, staging / "report.pdf", compare=compare)
            pdf_path = out_dir / "report.pdf"
        made: list[str] = []
        if certificate or dcc:
            from axiscal.report.dcc import dcc_xml

            xml = dcc_xml(results)
            (staging / "dcc.xml").write_bytes(xml)
            if certificate:
                from axiscal.report.certificate import render_certificate_html
                from axiscal.report.pdf import write_pdf

                language = results.issuer["certificate"].get("languages", ["en"])[0]
                (staging / "certificate.html").write_text(
                    render_certificate_html(results, language=language, compare=compare), encoding="utf-8")
                write_pdf(results, staging / "certificate.pdf", compare=compare, certificate_language=language, dcc=xml)
                made = ["certificate.html", "certificate.pdf"]
        return written, pdf_path, made

    written, pdf_path, made = atomic_folder(out_dir, fill)
    return ReportFiles(out_dir, out_dir / "report.html", out_dir / "results.json", pdf_path, tuple(written), results,
                       history=None if history is None else dict(history),
                       certificate=tuple(out_dir / name for name in made),
                       dcc=out_dir / "dcc.xml" if certificate or dcc else None)


def report_campaign(
    campaign_dir: str | Path,
    out_dir: str | Path | None = None,
    *,
    compare: str | Path | None = None,
    pdf: bool = False,
    progress: Callable[[int, int, TestSpec], None] | None = None,
    history: bool = False,
    db: str | None = None,
    recorded_as: str | Path | None = None,
    certificate: bool = False,
    dcc: bool = False,
) -> ReportFiles:
    """Run a campaign and write its report: what ``axiscal report`` does.

    Parameters
    ----------
    campaign_dir : str or Path
        The campaign folder (with campaign.toml).
    out_dir : str or Path, optional
        The report folder (default: ``CAMPAIGN_DIR/report``).
    compare : str or Path, keyword-only
        results.json of another campaign to compare with.
    pdf : bool, keyword-only
        Also write report.pdf.
    progress : callable, keyword-only
        See :func:`~axiscal.campaign.runner.run_campaign`.
    history : bool, keyword-only
        Also store the campaign in the calibration history and add its history section.
    db : str, keyword-only
        The history database (default ``$AXISCAL_DB``, else the user's SQLite file).
    recorded_as : str or Path, keyword-only
        The report folder the history records as the campaign's source (default: the folder
        written), for a report built in one place and moved to another (a fleet's reports are
        built beside their destination).
    certificate, dcc : bool, keyword-only
        Also write the calibration certificate and the DCC (see :func:`write_report`); the campaign
        must state the certificate's fields, else nothing is written.

    Returns
    -------
    ReportFiles

    Raises
    ------
    AxiscalError
        For a bad campaign, data file or comparison file; nothing is written then.

    Examples
    --------
    >>> files = report_campaign("examples/campaign", "/tmp/report")  # doctest: +SKIP
    >>> files.results_data.verdict  # doctest: +SKIP
    'fail'
    """
    campaign_dir = check_path("campaign_dir", campaign_dir)  # the one check of the folder's path
    if out_dir is not None:
        check_path("out_dir", out_dir)
    if compare is not None:
        compare = check_path("compare", compare)
    check_instance("pdf", pdf, bool)
    check_instance("history", history, bool)
    check_instance("certificate", certificate, bool)
    check_instance("dcc", dcc, bool)
    if db is not None and not history:
        raise AxiscalError("db applies only with history=True")
    if recorded_as is not None:
        recorded_as = check_path("recorded_as", recorded_as)
        if not history:
            raise AxiscalError("recorded_as applies only with history=True")
    campaign: Campaign = read_campaign(campaign_dir)
    other = None
    if compare is not None:
        other = read_compared(compare)
    try:
        results = run_campaign(campaign, progress=progress, compare=other)
    except AxiscalError as exc:
        if other is not None and exc.path is None and "compared results.json" in exc.message:
            raise exc.located(path=compare) from None  # a series of the other campaign that cannot be drawn
        raise
    if certificate or dcc:
        from axiscal.report.certificate import check_certificate

        check_certificate(results, campaign.folder / "campaign.toml")  # before anything is written
    target = Path(out_dir) if out_dir is not None else campaign.folder / "report"
    files = {entry["file"]: entry["text"] for t in results.tests for entry in t.compensation if "text" in entry}
    section = None
    if history:
        from axiscal.report.history import history_section

        section = history_section(results, url=db, source=str((recorded_as or target) / "results.json"))
    return write_report(results, target, compare=other, pdf=pdf, extra_files=files, history=section,
                        certificate=certificate, dcc=dcc)


def read_compared(path: Path) -> dict[str, Any]:
    """An earlier visit's figures to compare with: its results.json, or the DCC of its certificate.

    Parameters
    ----------
    path : Path
        ``results.json`` (schema axiscal-results/1) or ``dcc.xml`` written by axiscal.

    Returns
    -------
    dict
        A results.json object.

    Raises
    ------
    AxiscalError
        For a file that is neither.
    """
    path = check_path("path", path)
    if path.suffix.lower() == ".xml":
        from axiscal.report.dcc import read_dcc

        return read_dcc(path)
    other = read_json(path)
    if not isinstance(other, dict) or other.get("schema") != "axiscal-results/1":
        raise AxiscalError("not an axiscal results.json (schema axiscal-results/1) nor a dcc.xml", path=path)
    return other
