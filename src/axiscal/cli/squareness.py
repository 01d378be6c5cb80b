"""``axiscal squareness``, ``axiscal optics pentaprism``, ``axiscal cmm compensate|gauge-blocks``.

Squareness from two straightness runs (paper 002), the pentaprism's sensitivity to its set-up
(paper 002 Fig. 5) and the squareness compensation of a CMM (paper 004 eq 6). Values are typed in
the units their flags name; the computing is done in SI by :mod:`axiscal.squareness.evaluation`,
:mod:`axiscal.instruments.optics` and :mod:`axiscal.squareness.cmm`.
"""

from __future__ import annotations

import math

import click
import numpy as np

from axiscal.cli.common import echo_json, pyplot, write_output
from axiscal.errors import AxiscalError
from axiscal.instruments.optics import (
    BK7_INDEX,
    PentaprismSensitivity,
    pentaprism_sensitivity,
)
from axiscal.io.tabular import read_csv, write_csv
from axiscal.squareness.cmm import (
    CmmSquareness,
    compensate,
    readings_for,
    simulate_gauge_block,
)
from axiscal.squareness.evaluation import (
    PLANES,
    SquarenessResult,
    read_straightness_run,
    squareness,
)
from axiscal.units import ARCMIN, ARCSEC, MM, UM

__all__ = [
    "PAPER_004_IMPROVEMENT_UM",
    "MAX_CMM_SQUARENESS_ARCMIN",
    "squareness_payload",
    "squareness_report",
    "plot_squareness",
    "squareness_command",
    "pentaprism_payload",
    "pentaprism_report",
    "plot_pentaprism",
    "optics_group",
    "pentaprism_command",
    "parse_squareness_arcmin",
    "cmm_group",
    "compensate_command",
    "gauge_blocks_command",
    "register",
]

#: paper 004, Table 2 as its text gives it: error reductions by compensation, um
PAPER_004_IMPROVEMENT_UM = {"X": 11.0, "Y": 5.0}
#: Largest CMM squareness accepted on the command line, arc minutes: eq (6) is a small-angle model.
MAX_CMM_SQUARENESS_ARCMIN = 60.0


def squareness_payload(result: SquarenessResult, *, reference: str) -> dict:
    """The JSON object of ``axiscal squareness --json`` (angles in arcsec and degrees)."""
    first, second = result.first_line, result.second_line
    return {
        "plane": result.plane,
        "convention": result.convention,
        "squareness_arcsec": result.squareness_rad / ARCSEC,
        "included_angle_deg": math.degrees(result.included_angle_rad),
        "measured_included_angle_deg": math.degrees(result.measured_included_angle_rad),
        "prism_deviation_arcsec": result.prism_deviation_rad / ARCSEC,
        "iso_term": result.iso_term,
        "iso_value_arcsec": result.iso_value_rad / ARCSEC,
        "slope_first": result.slope_first,
        "slope_second": result.slope_second,
        "reference": reference,
        "straightness_first_um": None if first is None else first.straightness_m / UM,
        "straightness_second_um": None if second is None else second.straightness_m / UM,
    }


def squareness_report(result: SquarenessResult, first_path: str, second_path: str) -> str:
    """The readable summary of ``axiscal squareness``."""
    a, b = PLANES[result.plane][:2]
    name = "ISO 230-1 sign" if result.convention == "iso" else "included angle - 90 deg"
    rows = [
        ("slope of the first run", f"{result.slope_first:+.8f}  ({math.atan(result.slope_first) / ARCSEC:+.2f} arcsec)"),
        ("slope of the second run", f"{result.slope_second:+.8f}  ({math.atan(result.slope_second) / ARCSEC:+.2f} arcsec)"),
        ("included angle of the lines", f"{math.degrees(result.measured_included_angle_rad):.6f} deg"),
        ("prism deviation removed", f"{result.prism_deviation_rad / ARCSEC:+.2f} arcsec (paper 002 eq 21)"),
        ("included angle of the axes", f"{math.degrees(result.included_angle_rad):.6f} deg"),
        (f"squareness ({name})", f"{result.squareness_rad / ARCSEC:+.2f} arcsec"),
        (f"{result.iso_term} (ISO 230-1)", f"{result.iso_value_rad / ARCSEC:+.2f} arcsec"),
    ]
    lines = [f"squareness of {a}{b}: first run {first_path} (moves {a}), second run {second_path} (moves {b})"]
    lines += [f"  {label:<36}  {value}" for label, value in rows]
    return "\n".join(lines)


def plot_squareness(result: SquarenessResult, runs: tuple[tuple[np.ndarray, np.ndarray], ...], path: str) -> None:
    """Both runs with their fitted lines, deviation in um against position in mm."""
    plt = pyplot()
    a, b = PLANES[result.plane][:2]
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    for ax, (position, deviation), line, (moving, across) in zip(
        axes, runs, (result.first_line, result.second_line), ((a, b), (b, a))
    ):
        ax.plot(position / MM, deviation / UM, "o", ms=4, label="measured")
        ends = np.array([position.min(), position.max()])
        ax.plot(ends / MM, (line.slope * ends + line.intercept_m) / UM, "-", label=f"{line.reference} line")
        ax.set_xlabel(f"{moving} position / mm")
        ax.set_ylabel(f"deviation along {across} / um")
        ax.set_title(f"{moving} run: slope {line.slope:+.3e} ({math.atan(line.slope) / ARCSEC:+.2f} arcsec)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(
        f"{a}{b}: included angle - 90 deg - D = {(result.included_angle_rad - math.pi / 2) / ARCSEC:+.2f} arcsec"
        f"  ({result.iso_term} {result.iso_value_rad / ARCSEC:+.2f} arcsec)"
    )
    try:
        write_output(path, lambda target: fig.savefig(target, dpi=110))
    finally:
        plt.close(fig)


@click.command("squareness")
@click.option("--first", "first_csv", required=True, type=click.Path(dir_okay=False),
              help="Run of the plane's first axis: position_mm, deviation_um (deviation along the second axis).")
@click.option("--second", "second_csv", required=True, type=click.Path(dir_okay=False),
              help="Run of the plane's second axis: position_mm, deviation_um (deviation along the first axis).")
@click.option("--plane", default="XY", show_default=True, help="XY (EC0Y), XZ (EB0Z) or YZ (EA0Z).")
@click.option("--prism-deviation-arcsec", type=float, default=0.0, show_default=True,
              help="D: the prism turns the beam by 90 deg + D (paper 002 eq 13); subtracted per eq 21. "
              "Sign for a beam arriving against the first axis and leaving along the second; "
              "give -D if one of the two runs the other way (docs/squareness.md).")
@click.option("--reference", default="least-squares", show_default=True, help="least-squares or end-points line per run.")
@click.option("--convention", default="included-angle", show_default=True,
              help="Sign of squareness_arcsec: included-angle (included angle - 90 deg - D, paper 002 eq 21) "
              "or iso (the ISO 230-1 term's right-hand-rule sign).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write both runs and their lines to this image.")
def squareness_command(first_csv, second_csv, plane, prism_deviation_arcsec, reference, convention, as_json, plot_path):
    """Squareness of two axes from two straightness runs (paper 002 eqs 1 and 21)."""
    if reference not in ("least-squares", "end-points"):
        raise AxiscalError(f"--reference must be least-squares or end-points, not '{reference}'")
    if not math.isfinite(prism_deviation_arcsec):
        raise AxiscalError("--prism-deviation-arcsec must be a finite number")
    runs = (read_straightness_run(first_csv), read_straightness_run(second_csv))
    result = squareness(
        *runs[0], *runs[1],
        plane=plane.upper(),
        prism_deviation_rad=prism_deviation_arcsec * ARCSEC,
        reference=reference,
        convention=convention,
    )
    if plot_path:
        plot_squareness(result, runs, plot_path)
    if as_json:
        echo_json(squareness_payload(result, reference=reference))
    else:
        click.echo(squareness_report(result, first_csv, second_csv))


def pentaprism_payload(table: PentaprismSensitivity) -> dict:
    """The JSON object of ``axiscal optics pentaprism --json``."""
    return {
        "index": table.index,
        "rotation_arcmin": table.rotation_rad / ARCMIN,
        "deviation_change_arcsec": {axis: table.change_rad[k] / ARCSEC for k, axis in enumerate("XYZ")},
        "translation_mm": table.translation_m / MM,
        "translation_deviation_change_arcsec": {
            axis: table.translation_change_rad[k] / ARCSEC for k, axis in enumerate("XYZ")
        },
        "quadratic_coefficient_per_rad": table.quadratic_coefficient,
        "quadratic_coefficient_arcsec": table.quadratic_coefficient * ARCSEC,
    }


def _arcsec(value_rad: float) -> str:
    """Arc seconds to 4 places, without a minus sign on a rounded zero."""
    return f"{round(value_rad / ARCSEC, 4) + 0.0:>14.4f}"


def pentaprism_report(table: PentaprismSensitivity) -> str:
    """The readable table of ``axiscal optics pentaprism``."""
    lines = [
        f"pentaprism of paper 002 (index {table.index:g}): angle between incident and exit beam minus 90 deg",
        "",
        f"{'rotation_arcmin':>16}  {'about X_arcsec':>14}  {'about Y_arcsec':>14}  {'about Z_arcsec':>14}",
    ]
    for k, angle in enumerate(table.rotation_rad):
        cells = "  ".join(_arcsec(table.change_rad[axis, k]) for axis in range(3))
        lines.append(f"{angle / ARCMIN:>16.2f}  {cells}")
    lines += ["", f"{'translation_mm':>16}  {'along X_arcsec':>14}  {'along Y_arcsec':>14}  {'along Z_arcsec':>14}"]
    for k, shift in enumerate(table.translation_m):
        cells = "  ".join(_arcsec(table.translation_change_rad[axis, k]) for axis in range(3))
        lines.append(f"{shift / MM:>16.2f}  {cells}")
    lines += [
        "",
        f"rotation about Z: change = -{table.quadratic_coefficient:.6f} gamma^2 (rad), "
        f"= -{table.quadratic_coefficient * ARCSEC:.5e} gamma^2 in arcsec (paper 002 eq 12: 4.84803e-6)",
    ]
    return "\n".join(lines)


def plot_pentaprism(table: PentaprismSensitivity, path: str) -> None:
    """Paper 002 Fig. 5: the change of the deviation against rotation about X, Y, Z, and against shifts."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 4, figsize=(13, 3.6), sharey=True, constrained_layout=True)
    rotation_arcmin = table.rotation_rad / ARCMIN
    for k, ax in enumerate(axes[:3]):
        ax.plot(rotation_arcmin, table.change_rad[k] / ARCSEC, "-o", ms=3, label="ray trace")
        ax.set_title(f"({'abc'[k]}) rotation about {'XYZ'[k]}")
        ax.set_xlabel("rotation / arcmin")
        ax.grid(True, alpha=0.3)
    fine = np.linspace(table.rotation_rad.min(), table.rotation_rad.max(), 200)
    axes[2].plot(fine / ARCMIN, -(fine**2) / ARCSEC, "--", color="tab:red", label="eq (12): -gamma^2 (rad)")
    axes[2].legend(fontsize=8, loc="lower center")
    for k, marker in enumerate("os^"):
        # falling marker sizes keep all three visible where they coincide (all zero)
        axes[3].plot(table.translation_m / MM, table.translation_change_rad[k] / ARCSEC, marker + "-", ms=8 - 2 * k,
                     label=f"along {'XYZ'[k]}")
    axes[3].set_title("(d) translation: no effect")
    axes[3].set_xlabel("shift / mm")
    axes[3].grid(True, alpha=0.3)
    axes[3].legend(fontsize=8, loc="lower center")
    axes[0].set_ylabel("angle between beams - 90 deg / arcsec")
    fig.suptitle(f"pentaprism of paper 002, index {table.index:g}: incident beam [-1, 0, 0]")
    try:
        write_output(path, lambda target: fig.savefig(target, dpi=110))
    finally:
        plt.close(fig)


@click.group("optics")
def optics_group() -> None:
    """Ray-vector tracing through prisms (paper 002 section 3)."""


@optics_group.command("pentaprism")
@click.option("--index", type=float, default=BK7_INDEX, show_default=True, help="Refractive index of the glass.")
@click.option("--range-arcmin", type=float, default=10.0, show_default=True, help="Sweep rotations from -R to +R.")
@click.option("--steps", type=int, default=21, show_default=True, help="Number of rotation angles in the sweep.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False),
              help="Write Fig. 5 (rotation about X, Y, Z; translation) to this image.")
def pentaprism_command(index, range_arcmin, steps, as_json, plot_path):
    """Deviation of the pentaprism against its rotation about X, Y, Z and its translation (Fig. 5)."""
    if not (math.isfinite(range_arcmin) and 0 < range_arcmin <= 600):
        raise AxiscalError(f"--range-arcmin must be in (0, 600], got {range_arcmin}")
    if not 2 <= steps <= 2001:
        raise AxiscalError(f"--steps must be 2 to 2001, got {steps}")
    angles = np.linspace(-range_arcmin, range_arcmin, steps) * ARCMIN
    table = pentaprism_sensitivity(angles, np.linspace(-2.0, 2.0, 5) * MM, index=index)
    if plot_path:
        plot_pentaprism(table, plot_path)
    if as_json:
        echo_json(pentaprism_payload(table))
    else:
        click.echo(pentaprism_report(table))


def parse_squareness_arcmin(text: str) -> CmmSquareness:
    """``"8.05,27.1,-16.6"`` (a_xy, a_xz, a_yz in arc minutes, included-angle signs) -> CmmSquareness."""
    parts = text.split(",")
    try:
        values = [float(p) for p in parts]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise AxiscalError(f"--squareness-arcmin needs three numbers a_xy,a_xz,a_yz (e.g. 8.05,27.1,-16.6), got '{text}'")
    if any(abs(v) > MAX_CMM_SQUARENESS_ARCMIN for v in values):
        raise AxiscalError(
            f"--squareness-arcmin values must be within +-{MAX_CMM_SQUARENESS_ARCMIN:g} arc minutes "
            f"(eq 6 is a small-angle model; check the unit), got '{text}'"
        )
    return CmmSquareness(*(v * ARCMIN for v in values))


_SQUARENESS_HELP = (
    "a_xy,a_xz,a_yz in arc minutes: each the included angle of the two axes minus 90 deg "
    "(paper 004's signs; as ISO terms EC0Y = a_xy, EB0Z = -a_xz, EA0Z = a_yz)."
)


@click.group("cmm")
def cmm_group() -> None:
    """Squareness compensation of a coordinate measuring machine (paper 004)."""


@cmm_group.command("compensate")
@click.argument("points_csv", type=click.Path(dir_okay=False))
@click.option("--squareness-arcmin", required=True, help=_SQUARENESS_HELP)
@click.option("-o", "--output", "output", type=click.Path(dir_okay=False), help="Write the CSV here (default: stdout).")
@click.option("--inverse", is_flag=True, help="Go the other way: from true coordinates to the readings the CMM shows.")
def compensate_command(points_csv, squareness_arcmin, output, inverse):
    """Correct CMM readings by eq (6): x' = x - y a_xy - z a_xz, y' = y - z a_yz (POINTS_CSV: x_mm, y_mm, z_mm)."""
    values = parse_squareness_arcmin(squareness_arcmin)
    table = read_csv(points_csv)
    table.require("x_mm", "y_mm", "z_mm")
    points = np.column_stack([table.numeric(name) for name in ("x_mm", "y_mm", "z_mm")]) * MM
    moved = readings_for(points, values) if inverse else compensate(points, values)
    suffix = "reading" if inverse else "corrected"
    columns: dict = {name: table.text(name) for name in table.header}
    for k, axis in enumerate("xyz"):
        columns[f"{axis}_{suffix}_mm"] = moved[:, k] / MM
    sign = "EC0Y = a_xy, EB0Z = -a_xz, EA0Z = a_yz"
    comments = [
        f"paper 004 eq (6) {'inverse ' if inverse else ''}with a_xy, a_xz, a_yz = "
        f"{values.xy_rad / ARCMIN:g}, {values.xz_rad / ARCMIN:g}, {values.yz_rad / ARCMIN:g} arcmin ({sign})"
    ]
    text = write_csv(None, columns, fmt="{:.6f}", comments=comments)
    if output:
        write_output(output, lambda target: target.write_text(text, encoding="utf-8"))
    else:
        click.echo(text, nl=False)


@cmm_group.command("gauge-blocks")
@click.option("--squareness-arcmin", default="8.05,27.1,-16.6", show_default=True, help=_SQUARENESS_HELP)
@click.option("--end-offset-mm", type=float, default=1.0, show_default=True,
              help="Sideways distance, in each of the two across directions, between the two probed end points.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def gauge_blocks_command(squareness_arcmin, end_offset_mm, as_json):
    """Simulate paper 004's gauge block check (0.992 mm along X, 1.000 mm along Y) before and after eq (6)."""
    values = parse_squareness_arcmin(squareness_arcmin)
    if not (math.isfinite(end_offset_mm) and abs(end_offset_mm) <= 100):
        raise AxiscalError(f"--end-offset-mm must be within +-100, got {end_offset_mm}")
    d = end_offset_mm * MM
    blocks = {
        "X": simulate_gauge_block(values, 0.992 * MM, (1, 0, 0), end_offset_m=(0, d, d)),
        "Y": simulate_gauge_block(values, 1.000 * MM, (0, 1, 0), end_offset_m=(d, 0, -d)),
    }
    body = {
        axis: {
            "nominal_mm": check.nominal_m / MM,
            "aligned_before_um": check.aligned_before_m / UM,
            "aligned_after_um": check.aligned_after_m / UM,
            "aligned_improvement_um": check.aligned_improvement_m / UM,
            "unaligned_before_um": check.unaligned_before_m / UM,
            "unaligned_after_um": check.unaligned_after_m / UM,
            "unaligned_improvement_um": check.unaligned_improvement_m / UM,
            "paper_004_improvement_um": PAPER_004_IMPROVEMENT_UM[axis],
        }
        for axis, check in blocks.items()
    }
    if as_json:
        echo_json({"end_offset_mm": end_offset_mm, "blocks": body})
        return
    lines = [
        "gauge blocks on a CMM out of square (errors in um, measured - nominal)",
        f"end points {end_offset_mm:g} mm apart across the block in each direction",
        "",
        f"{'block':>10}  {'aligned before':>14}  {'after':>8}  {'unaligned before':>16}  {'after':>8}  {'improvement':>11}  {'paper 004':>9}",
    ]
    for axis, row in body.items():
        lines.append(
            f"{row['nominal_mm']:>7.3f} {axis}  {row['aligned_before_um']:>14.4f}  {row['aligned_after_um']:>8.4f}"
            f"  {row['unaligned_before_um']:>16.4f}  {row['unaligned_after_um']:>8.4f}"
            f"  {row['unaligned_improvement_um']:>11.2f}  {row['paper_004_improvement_um']:>9.1f}"
        )
    lines += [
        "",
        "aligned: the paper's procedure (6-point plane normal, projected length); unaligned: the",
        "point-to-point length along the machine axis. docs/squareness.md explains the difference.",
    ]
    click.echo("\n".join(lines))


def register(group: click.Group) -> None:
    group.add_command(squareness_command)
    group.add_command(optics_group)
    group.add_command(cmm_group)
