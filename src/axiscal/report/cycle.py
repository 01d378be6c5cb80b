"""The closed calibration cycle on a real controller: as found, compensation, the controller restarted with it, as left.

:func:`closed_cycle` is ``axiscal cycle``. The as-found run is driven and read
(:func:`axiscal.capture.connected.run_to_file`) into ``OUTPUT/as-found/campaign``, whose report
(``OUTPUT/as-found/report``) holds the controller's compensation file. The controller then has to load it:
the virtual controller (``sim``) loads it at once; for a real one a restart callable or command does it
(LinuxCNC reads ``[JOINT_n] COMP_FILE`` at start only, and must be homed again after), or the cycle says
exactly what to do and waits. The as-left run follows into ``OUTPUT/as-left/campaign``, reported compared
with the as-found results; ``OUTPUT/cycle.json`` holds both figures.
"""

from __future__ import annotations

import os
import shlex
import subprocess
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from axiscal.capture.connected import open_run_devices, run_to_file, sim_machine
from axiscal.capture.drive import DriveSettings
from axiscal.capture.run import CaptureSettings
from axiscal.devices.instruments import InstrumentOptions, default_stability_m
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_instance, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import read_json, write_json
from axiscal.io.templates import render_template
from axiscal.report.writer import report_campaign

__all__ = ["CycleSettings", "CycleResult", "closed_cycle"]


@dataclass(frozen=True)
class CycleSettings:
    """How the cycle loads the compensation and reads the instrument.

    Attributes
    ----------
    fmt : str
        The compensation file's format (``linuxcnc``).
    restart_command : str or None
        A shell command that restarts the controller with the file loaded and homes it; it runs with
        ``AXISCAL_COMP_FILE`` (the file's path) and ``AXISCAL_COMP_TYPE`` (1) in its environment.
    restart : callable or None
        The same as a Python callable, given the file's path (tests, the workbench).
    ini : str or None
        LinuxCNC's INI file (soft limits).
    seed : int
        Noise seed of a simulated instrument.
    stability_given : bool
        Whether the stability was given (else a gauge's follows its resolution).
    tolerance_e_um : float or None, um
        The tolerance of ISO 230-2's E held against both runs (none: figures reported, not assessed).
    """

    fmt: str = "linuxcnc"
    restart_command: str | None = None
    restart: Callable[[Path], None] | None = None
    ini: str | None = None
    seed: int = 0
    stability_given: bool = True
    tolerance_e_um: float | None = None

    def __post_init__(self) -> None:
        if self.tolerance_e_um is not None and not (isinstance(self.tolerance_e_um, float) and 0 < self.tolerance_e_um < 1e6):
            raise AxiscalError(f"tolerance_e_um must be a positive number of um, not {self.tolerance_e_um!r}")
        check_choice("fmt", self.fmt, ("linuxcnc",))
        if self.restart_command is not None:
            check_instance("restart_command", self.restart_command, str)
        if self.restart is not None and not callable(self.restart):
            raise AxiscalError(f"restart must be a function of the compensation file's path, not {type(self.restart).__name__}")


@dataclass(frozen=True)
class CycleResult:
    """What the cycle wrote.

    Attributes
    ----------
    folder : Path
    compensation : Path
        The compensation file loaded between the runs.
    summary : dict
        ``as_found`` and ``as_left`` (E_um, verdict, run CSV), ``ratio`` (as-left E / as-found E).
    """

    folder: Path
    compensation: Path
    summary: dict[str, Any]


def _campaign(folder: Path, title: str, axis: str, fmt: str, *, machine: str, instrument: str, wavelength_nm: float,
              tolerance_e_um: float | None) -> None:
    import datetime

    write_text(folder / "campaign.toml", render_template(
        "cycle_campaign.toml.j2", title=title, axis=axis, controller=fmt, date=datetime.date.today().isoformat(),
        machine=f"the machine on {machine}", instrument=instrument, wavelength_nm=repr(wavelength_nm),
        tolerance_e_um=None if tolerance_e_um is None else repr(tolerance_e_um)))


def _figures(report: Path, run_csv: Path) -> dict[str, Any]:
    results = read_json(report / "results.json")
    test = results["tests"][0]
    return {"E_um": float(test["figures"]["E"]), "verdict": test["verdict"], "run_csv": str(run_csv),
            "report": str(report / "report.html")}


def closed_cycle(
    plan: str | Path,
    controller: str,
    source: str,
    output_dir: str | Path,
    cycle: CycleSettings | None = None,
    *,
    drive: DriveSettings | None = None,
    settings: CaptureSettings | None = None,
    options: InstrumentOptions | None = None,
    ask: Callable[[str], None] | None = None,
    note: Callable[[str], None] | None = None,
) -> CycleResult:
    """As found -> compensation -> the controller loads it -> as left -> the compared report.

    Parameters
    ----------
    plan : str or Path
        The plan's cycle CSV.
    controller, source : str
        As ``axiscal run`` takes them.
    output_dir : str or Path
        The cycle's folder.
    cycle : CycleSettings, optional
    drive, settings, options : keyword-only
        As :func:`axiscal.capture.connected.run_to_file` and the instrument opener take them.
    ask : callable, keyword-only
        Called with the instructions when the user must load the file by hand; returns once done.
    note : callable, keyword-only
        Called with each progress note.

    Returns
    -------
    CycleResult

    Raises
    ------
    AxiscalError
        As ``axiscal run``; for a restart command that fails; for no way to load the file (neither a
        restart nor ``ask``).
    """
    cycle = CycleSettings() if cycle is None else check_instance("cycle", cycle, CycleSettings)
    drive = DriveSettings() if drive is None else check_instance("drive", drive, DriveSettings)
    settings = CaptureSettings() if settings is None else check_instance("settings", settings, CaptureSettings)
    check_instance("controller", controller, str, what="a controller spec such as 'linuxcnc:127.0.0.1'")
    check_instance("source", source, str, what="an instrument spec such as 'umd:/dev/ttyACM0'")
    folder = check_path("output_dir", output_dir)
    say = note or (lambda text: None)
    axis = drive.axis.strip().upper()
    machine = sim_machine(axis=axis) if controller.strip().lower() == "sim" else None

    wavelength_nm = (InstrumentOptions() if options is None else options).wavelength_m * 1e9

    def one_run(stage: str, machine_now) -> tuple[Path, Path]:
        campaign = folder / stage / "campaign"
        campaign.mkdir(parents=True, exist_ok=True)
        run_csv = campaign / "run.csv"
        made, instrument = open_run_devices(controller, source, options=options, ini=cycle.ini, machine=machine_now,
                                            seed=cycle.seed)
        try:
            used = settings if cycle.stability_given else CaptureSettings(
                stability_m=default_stability_m(instrument, None), window_s=settings.window_s, offset_m=settings.offset_m)
            description = f"{instrument.status.description}"
            say(f"{stage}: driving the plan on {made.description}, reading {description}")
            run_to_file(plan, made, instrument, run_csv, drive=drive, settings=used, resume=(campaign / "run.csv.partial").is_file())
        finally:
            instrument.close()
            made.close()
        title = "as found" if stage == "as-found" else "as left"
        _campaign(campaign, f"{axis} axis {title} ({controller})", axis, cycle.fmt, machine=controller,
                  instrument=description, wavelength_nm=wavelength_nm, tolerance_e_um=cycle.tolerance_e_um)
        return campaign, run_csv

    found_campaign, found_csv = one_run("as-found", machine)
    found_report = folder / "as-found" / "report"
    report_campaign(found_campaign, found_report)
    comp = found_report / "compensation" / f"{axis}.comp"
    if not comp.is_file():
        raise AxiscalError(f"the as-found report wrote no compensation file for {axis}", path=found_report)
    say(f"compensation written: {comp}")
    if machine is not None:
        from axiscal.compensation.readback import read_compensation

        machine = sim_machine(axis=axis, compensation=read_compensation(comp.read_text(encoding="utf-8"), "linuxcnc", comp_type=1))
    elif cycle.restart is not None:
        cycle.restart(comp.resolve())
    elif cycle.restart_command:
        say(f"restarting the controller: {cycle.restart_command}")
        env = {**os.environ, "AXISCAL_COMP_FILE": str(comp.resolve()), "AXISCAL_COMP_TYPE": "1"}
        done = subprocess.run(shlex.split(cycle.restart_command), env=env, capture_output=True, text=True)
        if done.returncode != 0:
            tail = (done.stderr or done.stdout).strip().splitlines()[-1:] or ["no message"]
            raise AxiscalError(f"the restart command failed (exit {done.returncode}): {tail[0]}")
    elif ask is not None:
        ask(f"load {comp.resolve()} into the controller: in the machine's INI file set [JOINT_0] COMP_FILE = {comp.resolve()}"
            f" and COMP_FILE_TYPE = 1 (the joint of axis {axis}), restart LinuxCNC, home the machine")
    else:
        raise AxiscalError("the controller must load the compensation file between the runs: give a restart command")
    left_campaign, left_csv = one_run("as-left", machine)
    left_report = folder / "as-left" / "report"
    report_campaign(left_campaign, left_report, compare=found_report / "results.json")
    found, left = _figures(found_report, found_csv), _figures(left_report, left_csv)
    summary = {"as_found": found, "as_left": left, "compensation": str(comp),
               "ratio": left["E_um"] / found["E_um"] if found["E_um"] else None}
    write_json(folder / "cycle.json", summary)
    return CycleResult(folder, comp, summary)
