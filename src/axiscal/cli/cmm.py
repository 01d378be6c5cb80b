"""``axiscal cmm``: the group, with ``acceptance`` (the ISO 10360-2 length test) and ``probing`` (the ISO 10360-5 probing test); it takes ``compensate`` and ``gauge-blocks`` from :mod:`axiscal.cli.squareness`, which knows nothing of the group."""

from __future__ import annotations

import click

from axiscal.cli.common import FINITE, echo_json, flags_named
from axiscal.cli.choices import DECISION_RULES
from axiscal.cli.squareness import compensate_command, gauge_blocks_command
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

__all__ = ["cmm_group", "acceptance_command", "probing_command"]

_RULE_HELP = ("guard-band (ISO 14253-1): a value proves conformance within MPE - U, non-conformance beyond MPE + U, "
              "no decision between; simple: against the MPE itself.")


@click.group("cmm")
def cmm_group() -> None:
    """Coordinate measuring machines: ISO 10360 length and probing tests, squareness compensation (paper 004)."""


def _bounded(values: dict[str, float | None], *, zero: bool = False) -> None:
    """Refuse a flag that is not positive (or, with ``zero``, negative), or beyond its range, naming the flag.

    A limit or an uncertainty in um (or um per metre) is at most 10000 (:data:`axiscal.cmm.mpe.LIMIT_M`), as
    a budget file's; K is 1 to 1000000 (:data:`axiscal.cmm.mpe.K_RANGE`); a diameter in mm has no bound here.
    """
    from axiscal.cmm.mpe import K_RANGE, LIMIT_M

    for flag, value in values.items():
        if value is None:
            continue
        if flag.endswith("-k"):
            low, high, unit = K_RANGE[0], K_RANGE[1], ""
        elif flag.endswith("-mm"):
            low, high, unit = 0.0, None, " of millimetres"
        else:
            low, high, unit = 0.0, LIMIT_M / UM, " of micrometres per metre" if flag.endswith("-per-m") else " of micrometres"
        if low > 0 and not low <= value <= high:
            raise AxiscalError(f"{flag} must be {low:g} to {high:g}, not {value:g}")
        if value < 0 or value == 0 and not zero:
            raise AxiscalError(f"{flag} must be a {'non-negative' if zero else 'positive'} number{unit}, not {value:g}")
        if high is not None and value > high:
            span = f"0 to {high:g}" if zero else f"above 0 and at most {high:g}"
            raise AxiscalError(f"{flag} must be {span}{unit.replace(' of ', ' ')}, not {value:g}")


def _mpe(prefix: str, a_um: float | None, k: float | None, b_um: float | None):
    from axiscal.cmm.mpe import Mpe

    _bounded({f"--{prefix}-a-um": a_um, f"--{prefix}-k": k, f"--{prefix}-b-um": b_um})
    if a_um is None:
        for flag, value in ((f"--{prefix}-k", k), (f"--{prefix}-b-um", b_um)):
            if value is not None:
                raise AxiscalError(f"{flag} needs --{prefix}-a-um (the MPE's constant A)")
        return None
    with flags_named({"a_m": f"--{prefix}-a-um", "k": f"--{prefix}-k", "b_m": f"--{prefix}-b-um"}):
        return Mpe(a_um * UM, k=k, b_m=None if b_um is None else b_um * UM)


@cmm_group.command("acceptance")
@click.argument("measurements", type=click.Path(dir_okay=False))
@click.option("--mpe-a-um", type=FINITE, help="E0,MPE = ±min(A + L/K, B): A in um.")
@click.option("--mpe-k", type=FINITE, help="K of E0,MPE (L in mm, L/K read in um); leave out for a constant MPE.")
@click.option("--mpe-b-um", type=FINITE, help="B of E0,MPE, the cap, in um (the min(...) form).")
@click.option("--e150-mpe-a-um", type=FINITE, help="A of E150,MPE (E150 is not assessed without it).")
@click.option("--e150-mpe-k", type=FINITE, help="K of E150,MPE.")
@click.option("--e150-mpe-b-um", type=FINITE, help="B of E150,MPE.")
@click.option("--r0-mpl-um", type=FINITE, help="R0,MPL: the largest permitted repeatability range, um.")
@click.option("--uncertainty-um", type=FINITE, default=0.0, show_default=True,
              help="U0: expanded test uncertainty (k = 2) at zero length, um.")
@click.option("--uncertainty-um-per-m", type=FINITE, default=0.0, show_default=True,
              help="Growth of U with length, um per metre: U(L) = U0 + L x this.")
@click.option("--decision-rule", type=click.Choice(tuple(DECISION_RULES)), default="guard-band", show_default=True,
              help=_RULE_HELP)
@click.option("--json", "as_json", is_flag=True,
              help="Print JSON: E0 and E150 (largest |E|, MPE, counts, decisive value, verdict), R0_um, verdict, measurements ...")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False),
              help="Write every error against its length with the MPE lines.")
def acceptance_command(measurements, mpe_a_um, mpe_k, mpe_b_um, e150_mpe_a_um, e150_mpe_k, e150_mpe_b_um, r0_mpl_um,
                       uncertainty_um, uncertainty_um_per_m, decision_rule, as_json, plot_path):
    """ISO 10360-2 length test of a CMM: E0, E150 and R0 from MEASUREMENTS (CSV: position, length, nominal_mm, measured_mm, repeat[, ram_offset_mm])."""
    _bounded({"--r0-mpl-um": r0_mpl_um})
    _bounded({"--uncertainty-um": uncertainty_um, "--uncertainty-um-per-m": uncertainty_um_per_m}, zero=True)
    mpe = _mpe("mpe", mpe_a_um, mpe_k, mpe_b_um)
    mpe_150 = _mpe("e150-mpe", e150_mpe_a_um, e150_mpe_k, e150_mpe_b_um)
    flags = {"r0_mpl_m": "--r0-mpl-um", "uncertainty_m": "--uncertainty-um", "uncertainty_per_m": "--uncertainty-um-per-m",
             "mpe": "--mpe-a-um", "mpe_150": "--e150-mpe-a-um"}
    with flags_named(flags):
        from axiscal.cmm.acceptance import evaluate_acceptance

        result = evaluate_acceptance(measurements, mpe=mpe, mpe_150=mpe_150,
                                     r0_mpl_m=None if r0_mpl_um is None else r0_mpl_um * UM,
                                     uncertainty_m=uncertainty_um * UM, uncertainty_per_m=uncertainty_um_per_m * UM,
                                     rule=decision_rule)
    if plot_path:
        from axiscal.cmm.plot import plot_acceptance

        plot_acceptance(plot_path, result)
    if as_json:
        echo_json(result.payload())
    else:
        click.echo(result.report())


_PROBING_MPE = {"pform": "--pform-mpe-um", "psize": "--psize-mpe-um", "pform_ms": "--pform-ms-mpe-um",
                "psize_ms": "--psize-ms-mpe-um", "ploc": "--ploc-mpe-um"}


@cmm_group.command("probing")
@click.argument("points", type=click.Path(dir_okay=False))
@click.option("--diameter-mm", type=FINITE, required=True, help="The test sphere's calibrated diameter, mm.")
@click.option("--pform-mpe-um", type=FINITE, help="PForm.Sph.1x25::SS:Tact,MPE, um.")
@click.option("--psize-mpe-um", type=FINITE, help="PSize.Sph.1x25::SS:Tact,MPE, um.")
@click.option("--pform-ms-mpe-um", type=FINITE, help="PForm.Sph.5x25::MS:Tact,MPE (several styli), um.")
@click.option("--psize-ms-mpe-um", type=FINITE, help="PSize.Sph.5x25::MS:Tact,MPE (several styli), um.")
@click.option("--ploc-mpe-um", type=FINITE, help="PLoc.Sph.5x25::MS:Tact,MPE (several styli), um.")
@click.option("--uncertainty-um", type=FINITE, default=0.0, show_default=True,
              help="Expanded test uncertainty (k = 2) of each figure, um.")
@click.option("--decision-rule", type=click.Choice(tuple(DECISION_RULES)), default="guard-band", show_default=True,
              help=_RULE_HELP)
@click.option("--json", "as_json", is_flag=True,
              help="Print JSON: figures (ISO name, value_um, mpe_um, verdict), pform_um, psize_um ..., styli, verdict.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False),
              help="Write the radial deviation of every point from its sphere.")
def probing_command(points, diameter_mm, pform_mpe_um, psize_mpe_um, pform_ms_mpe_um, psize_ms_mpe_um, ploc_mpe_um,
                    uncertainty_um, decision_rule, as_json, plot_path):
    """ISO 10360-5 probing test: form, size (and, with several styli, location) from POINTS on a sphere (CSV: [stylus,] x_mm, y_mm, z_mm)."""
    given = {"pform": pform_mpe_um, "psize": psize_mpe_um, "pform_ms": pform_ms_mpe_um, "psize_ms": psize_ms_mpe_um,
             "ploc": ploc_mpe_um}
    _bounded({"--diameter-mm": diameter_mm, **{_PROBING_MPE[k]: v for k, v in given.items()}})
    _bounded({"--uncertainty-um": uncertainty_um}, zero=True)
    mpe_m = {k: v * UM for k, v in given.items() if v is not None}
    flags = {"calibrated_diameter_m": "--diameter-mm", "uncertainty_m": "--uncertainty-um",
             **{f"mpe_m['{k}']": flag for k, flag in _PROBING_MPE.items()}}
    with flags_named(flags):
        from axiscal.cmm.probing import evaluate_probing

        result = evaluate_probing(points, calibrated_diameter_m=diameter_mm * MM, mpe_m=mpe_m,
                                  uncertainty_m=uncertainty_um * UM, rule=decision_rule)
    if plot_path:
        from axiscal.cmm.plot import plot_probing

        plot_probing(plot_path, result)
    if as_json:
        echo_json(result.payload())
    else:
        click.echo(result.report())


cmm_group.add_command(compensate_command)
cmm_group.add_command(gauge_blocks_command)
