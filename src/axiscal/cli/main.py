"""Entry point of the ``axiscal`` command.

User mistakes (:class:`axiscal.AxiscalError`) become one line on stderr, ``axiscal: error: FILE:LINE:
problem``, and exit status 2; no traceback. Usage errors from Click (a missing option, a flag given a
word where a number belongs) are one line too, naming the command's --help, with status 2.

The commands come from one table, :data:`COMMANDS`: a command's name, where it lives and its one-line
summary. ``axiscal --help`` prints the table without importing any command; running a command, or
asking for its ``--help``, imports its module only. Command modules import the library inside their
functions, so that ``--help`` and argument errors answer at once.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import click

from axiscal.errors import AxiscalError
from axiscal.version import __version__

__all__ = ["COMMANDS", "SIMULATE_COMMANDS", "LazyGroup", "cli", "main"]

# Click 8.2 and later raise this for a group called without its command; 8.1 printed the help itself
_NoArgsIsHelp = getattr(click.exceptions, "NoArgsIsHelpError", ())

#: command name -> ("module:attribute" of its click command, one-line summary; None hides the command).
#: A new command is one line here (a test checks each summary against the command's own help).
COMMANDS: dict[str, tuple[str, str | None]] = {
    "air": ("axiscal.cli.air:air_command", "Refractive index of air (Ciddor 1996, modified Edlen, Edlen 1966 or NIST shop-floor)."),
    "ballbar": ("axiscal.cli.ballbar:ballbar_command", "Evaluate a ballbar test (RUN.csv: angle_deg, direction ccw/cw, radius_deviation_um) to ISO 230-4, with diagnostics."),
    "calibrate": ("axiscal.cli.measure:calibrate_group", "Fit sensor calibrations against reference instruments into a calibration file (JSON)."),
    "capture": ("axiscal.cli.capture:capture_command", "Capture a positioning run: walk PLAN_CSV's steps through a recording (--from) or a live stream (--source)."),
    "cmm": ("axiscal.cli.cmm:cmm_group", "Coordinate measuring machines: ISO 10360 length and probing tests, squareness compensation (paper 004)."),
    "compensate": ("axiscal.cli.compensate:compensate_command", "Write a compensation table for the controller from the mean deviations of RUN_CSV (a linear or rotary axis)."),
    "cycle": ("axiscal.cli.run:cycle_command", "The closed cycle on a controller: as found -> compensation -> (restart with it) -> as left -> compared report."),
    "dcc": ("axiscal.cli.dcc:dcc_group", "Digital Calibration Certificates: sign, verify, show."),
    "demo": ("axiscal.cli.demo:demo_command", "Simulate a whole calibration campaign of paper 000's XZ module and report it."),
    "dynamics": ("axiscal.cli.dynamics:dynamics_command", "Dynamics of an axis from a timebase RECORDING: velocity, acceleration, jerk, spectrum, settling at each stop."),
    "diagonal": ("axiscal.cli.volumetric:diagonal_command", "Diagonal displacement test predicted by the model (ISO 230-6), and compared with an interferometer (paper 000 eq 13: E_BD before the model, E_AD after)."),
    "experiment": ("axiscal.cli.measure:experiment_group", "Paper experiments reproduced in simulation."),
    "export": ("axiscal.cli.export:export_group", "Write corrections in a firmware's or controller's own format (see docs/compensation.md)."),
    "flatness": ("axiscal.cli.flatness:flatness_command", "Flatness of the surface measured along the lines of LINES (TOML: [[lines]] with ends and readings or profiles)."),
    "fleet": ("axiscal.cli.fleet:fleet_group", "Many machines at once: campaigns reported in parallel, one page ranking the machines (docs/history.md)."),
    "fringes": ("axiscal.cli.air:fringes_command", "Length from a fringe count (paper 003 eq 1), compensated for the air and normalised to 20 degC."),
    "history": ("axiscal.cli.history:history_group", "Calibration history of machines in a database: drift and calibration intervals (docs/history.md)."),
    "identify": ("axiscal.cli.identify:identify_command", "Identify the error tables of MACHINE.toml from artefact measurements."),
    "import": ("axiscal.cli.importing:import_group", "Read an instrument's file into axiscal's CSV (see docs/importing.md)."),
    "inverse": ("axiscal.cli.volumetric:inverse_command", "Axis commands that put the tool point on wanted points (compensated commands, to < 1 nm)."),
    "levels": ("axiscal.cli.levels:levels_command", "Straightness and pitch (or roll) of RUN (CSV: position_mm and angle_arcsec, angle_urad or angle_um_per_m)."),
    "live": ("axiscal.cli.live:live", "Stream frames through the measurement chain live: spatial error of the functional point, recorded and shown."),
    "measure": ("axiscal.cli.measure:measure_command", "Process recorded raw frames offline: six errors per axis, spatial error, corrected position."),
    "on-the-fly": ("axiscal.cli.dynamics:on_the_fly_command", "Capture a positioning run on the fly: each target's reading where the position stream crosses it."),
    "optics": ("axiscal.cli.squareness:optics_group", "Ray-vector tracing through prisms (paper 002 section 3)."),
    "periodic": ("axiscal.cli.dynamics:periodic_command", "Periodic positioning error of RUN_CSV (a step cycle's run): amplitude and period by fit and by spectrum."),
    "plan": ("axiscal.cli.plan:plan_command", "Plan an ISO 230-2 positioning test: uneven targets and the test cycle (CSV to fill in; G-code with --gcode)."),
    "positioning": ("axiscal.cli.positioning:positioning_command", "Evaluate a positioning test (RUN_CSV: target_mm, run, direction, deviation_um or actual_mm; target_deg and deviation_arcsec for a rotary axis; one direction or both)."),
    "precompensate": ("axiscal.cli.precompensate:precompensate_command", "Rewrite a part program through the machine model: every point commanded where the tool lands on it."),
    "report": ("axiscal.cli.report:report_command", "Run every test of CAMPAIGN_DIR (campaign.toml) and write report.html, results.json and the compensation files."),
    "run": ("axiscal.cli.run:run_command", "Drive PLAN_CSV's steps on a controller and read the instrument at every target: the run `capture` writes."),
    "schema": ("axiscal.cli.schema:schema_command", "Print the JSON Schema of a TOML format (draft 7)."),
    "separate": ("axiscal.cli.separation:separate_command", "Separate workpiece profile and slide motion from READINGS (position_mm, a_um, b_um[, c_um])."),
    "simulate": ("axiscal.cli.main:simulate_group", "Simulated data: frames and laser readings of paper 000's XZ module, ballbar traces, probe readings, captures."),
    "simulate-probes": ("axiscal.cli.separation:simulate_probes_alias", None),
    "squareness": ("axiscal.cli.squareness:squareness_command", "Squareness of two axes from two straightness runs (paper 002 eqs 1 and 21)."),
    "straightness": ("axiscal.cli.straightness:straightness_command", "Straightness of PROFILE (CSV with position_mm, deviation_um): the zone's width about a reference line."),
    "thermal": ("axiscal.cli.thermal:thermal_group", "Thermal tests (ISO 230-3): environmental temperature variation error and thermal drift."),
    "uncertainty": ("axiscal.cli.uncertainty:uncertainty_group", "Measurement uncertainty (see docs/uncertainty.md; positioning U: axiscal positioning --uncertainty)."),
    "volumetric": ("axiscal.cli.volumetric:volumetric_command", "Volumetric error of the functional point at given axis positions."),
    "workbench": ("axiscal.cli.workbench:workbench", "Open the workbench: machines and their history, a new visit, plan, connect, run, results, compensate, finish."),
}

#: the commands of ``axiscal simulate``, as :data:`COMMANDS`
SIMULATE_COMMANDS: dict[str, tuple[str, str | None]] = {
    "ballbar": ("axiscal.cli.ballbar:simulate_ballbar_command", "Write the ballbar trace (angle_deg, direction, radius_deviation_um) of a virtual machine with the errors given."),
    "capture": ("axiscal.cli.capture:simulate_capture_command", "Run PROGRAM on the virtual machine and record what a laser on --axis reads over time."),
    "frames": ("axiscal.cli.measure:simulate_frames_command", "Raw frames of the virtual module: t_s and every channel, ready for `axiscal measure`."),
    "laser": ("axiscal.cli.measure:simulate_laser_command", "Laser interferometer readings on the XZ diagonal of the virtual module."),
    "probes": ("axiscal.cli.separation:simulate_probes_command", "Write the readings (position_mm, a_um, b_um[, c_um]) a probe set-up would give on a profile and a slide."),
}

#: modules of the package that hold helpers, not commands
_HELPERS = frozenset({"main", "common", "choices"})


class LazyGroup(click.Group):
    """A group whose commands are imported when needed, from a table or from a package's modules.

    Parameters
    ----------
    table : mapping of str to (str, str or None), optional
        Command name -> (``"module:attribute"`` of the command, its one-line summary, or None for a
        hidden command). ``--help`` lists these from the table, importing nothing; a command's
        module is imported when the command runs or shows its own help.
    package : str, optional
        A package whose modules not named in ``table`` may define ``register(group)`` to add their
        commands (a module added without its line in the table still works, only slower to list).
    """

    def __init__(self, *args: Any, table: Mapping[str, tuple[str, str | None]] | None = None,
                 package: str | None = None, **kwargs: Any):
        super().__init__(*args, **kwargs)
        self._table = dict(table or {})
        self._package = package
        self._loaded: set[str] = set()

    # --- the table -------------------------------------------------------------------------------
    def _resolve(self, name: str) -> click.Command:
        module, _, attribute = self._table[name][0].partition(":")
        command = getattr(importlib.import_module(module), attribute)
        self.add_command(command, name)
        return command

    # --- modules with register(group) that the table does not name ---------------------------------
    def _modules(self) -> list[tuple[str, Path]]:
        if self._package is None:
            return []
        package = importlib.import_module(self._package)
        tabled = {spec.partition(":")[0] for spec, _ in self._table.values()}
        return [
            (info.name, Path(info.module_finder.path) / f"{info.name}.py")  # type: ignore[union-attr]
            for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda m: m.name)
            if info.name not in _HELPERS and f"{self._package}.{info.name}" not in tabled
        ]

    def _load(self, name: str) -> None:
        if name in self._loaded:
            return
        self._loaded.add(name)
        module = importlib.import_module(f"{self._package}.{name}")
        register = getattr(module, "register", None)
        if register is not None:
            register(self)

    def load_all(self) -> None:
        """Import every command (those of the table and those of modules with ``register``)."""
        for name in self._table:
            if name not in self.commands:
                self._resolve(name)
        for name, _ in self._modules():
            self._load(name)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        command = self.commands.get(cmd_name)
        if command is not None:
            return command
        if cmd_name in self._table:
            return self._resolve(cmd_name)
        modules = self._modules()
        if not modules:
            return None
        spelled = (f'"{cmd_name}"', f"'{cmd_name}'")
        for name, source in modules:
            try:
                text = source.read_text(encoding="utf-8")
            except OSError:
                text = ""
            if name == cmd_name.replace("-", "_") or any(s in text for s in spelled):
                self._load(name)
        if cmd_name not in self.commands:
            for name, _ in modules:
                self._load(name)
        return self.commands.get(cmd_name)

    def list_commands(self, ctx: click.Context) -> list[str]:
        for name, _ in self._modules():
            self._load(name)
        return sorted(set(self._table) | set(self.commands))

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The commands with their summaries; a command of the table is listed without importing it."""
        rows: list[tuple[str, str | None, click.Command | None]] = []
        for name in self.list_commands(ctx):
            if name in self._table and name not in self.commands:
                summary = self._table[name][1]
                if summary is not None:
                    rows.append((name, summary, None))
                continue
            command = self.get_command(ctx, name)
            if command is not None and not command.hidden:
                rows.append((name, None, command))
        if not rows:
            return
        limit = formatter.width - 6 - max(len(name) for name, _, _ in rows)
        lines = [
            (name, (command or click.Command(name, help=summary)).get_short_help_str(limit))
            for name, summary, command in rows
        ]
        with formatter.section("Commands"):
            formatter.write_dl(lines)


_SETTINGS = {"help_option_names": ["-h", "--help"], "max_content_width": 100}


@click.group(cls=LazyGroup, table=COMMANDS, package="axiscal.cli", context_settings=_SETTINGS)
@click.version_option(__version__, prog_name="axiscal")
def cli() -> None:
    """Measure, model and compensate the geometric errors of machine axes.

    Python API in SI units; files and flags carry their units in their names (position_mm, EXX_um,
    --pressure-pa). See docs/ for conventions and file formats.
    """


@click.group("simulate", cls=LazyGroup, table=SIMULATE_COMMANDS)
def simulate_group() -> None:
    """Simulated data: frames and laser readings of paper 000's XZ module, ballbar traces, probe readings, captures."""


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status (tests call this directly)."""
    try:
        # outside standalone mode click returns ctx.exit(N)'s status (commands themselves return None)
        status = cli.main(args=list(argv) if argv is not None else None, prog_name="axiscal", standalone_mode=False)
    except AxiscalError as exc:
        click.echo(f"axiscal: error: {exc}", err=True)
        return 2
    except click.exceptions.Abort:
        click.echo("axiscal: aborted", err=True)
        return 1
    except _NoArgsIsHelp as exc:  # a bare `axiscal` or group: its help, as git and pip do
        click.echo(exc.ctx.get_help() if exc.ctx is not None else cli.get_help(click.Context(cli, info_name="axiscal")))
        return 0
    except click.UsageError as exc:
        command = exc.ctx.command_path if exc.ctx is not None else "axiscal"
        message = " ".join(exc.format_message().split())
        click.echo(f"axiscal: error: {message} (see '{command} --help')", err=True)
        return exc.exit_code
    except click.ClickException as exc:
        click.echo(f"axiscal: error: {' '.join(exc.format_message().split())}", err=True)
        return exc.exit_code
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except BrokenPipeError:
        return 0
    return status if isinstance(status, int) and not isinstance(status, bool) else 0


if __name__ == "__main__":
    sys.exit(main())
