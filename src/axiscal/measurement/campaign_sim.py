"""A whole calibration campaign of paper 000's XZ module, simulated by the virtual instrument.

Paper 000 (sections 4 and 5) on :class:`axiscal.measurement.virtual.VirtualModule`: the sensor
calibration (section 4.1), a 6-DOF recording along the diagonal with 2 kg on Z, ISO 230-2 laser
runs of X and Z as raw readings with air and material sensors (ISO 230-2:2014 clause 3; refractive
index by Ciddor, material normalised to 20 degC), the straightness EZX of X by three-probe error
separation (paper 001 eq 1), the squareness EB0Z by two straightness runs and a pentaprism (paper
002 eqs 1 and 21) and the ISO 230-6 diagonal check unloaded and with 2 kg (paper 000 eq 13).
:func:`write_campaign` writes them as a campaign folder in the formats of docs/campaign.md.

What the virtual module does not model is added here and stated with the value used: the axes'
reversal and repeatability in the laser runs (:data:`REVERSAL_M`, :data:`REPEATABILITY_M`), the
laboratory's air and the steel's temperature (:data:`AIR`), the straightedge under the probes
(:data:`STRAIGHTEDGE_M`) and the pentaprism's own deviation (:data:`PRISM_DEVIATION_RAD`).
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.instruments.abbe import transfer_point
from axiscal.instruments.air import refractive_index
from axiscal.instruments.calibration import save_calibration
from axiscal.io.arguments import check_count, check_instance, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.io.templates import render_template
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.measurement.frames import write_data_csv
from axiscal.measurement.virtual import (
    INTERFEROMETER_BEAM_M,
    REFERENCE_NOISE,
    STROKE_M,
    VirtualModule,
)
from axiscal.positioning.plan import plan_targets
from axiscal.straightness.separation import simulate_readings
from axiscal.units import ARCSEC, MM, UM

__all__ = [
    "AIR",
    "DIAGONAL_LOADS_KG",
    "campaign_toml",
    "PRISM_DEVIATION_RAD",
    "REPEATABILITY_M",
    "REVERSAL_M",
    "STRAIGHTEDGE_M",
    "VACUUM_WAVELENGTH_NM",
    "SimulatedCampaign",
    "diagonal_readings",
    "laser_run",
    "probe_readings",
    "squareness_runs",
    "write_campaign",
]

#: vacuum wavelength of the simulated He-Ne laser, nm
VACUUM_WAVELENGTH_NM = 632.99137
#: reversal (B of ISO 230-2) the simulated axes show in the laser runs, m
REVERSAL_M = {"X": 1.6 * UM, "Z": 2.2 * UM}
#: standard deviation of an axis' positioning scatter from approach to approach, m
REPEATABILITY_M = 0.25 * UM
#: the laboratory: air at the start (degC, Pa, %), its drift per run, and the steel's temperature (degC)
AIR = {"temperature_c": 21.2, "pressure_pa": 100850.0, "humidity_pct": 45.0, "drift_c_per_run": 0.04,
       "material_c": 20.8, "material_drift_c_per_run": 0.02}
#: form error of the straightedge under the probes: (amplitude m, cycles over its length, phase)
STRAIGHTEDGE_M = ((1.2 * UM, 1.0, 0.4), (0.4 * UM, 3.5, 1.1))
#: the pentaprism's deviation from 90 degrees (D of paper 002 eq 13), rad
PRISM_DEVIATION_RAD = 2.5 * ARCSEC
#: the loads on the Z slide of the two diagonal checks, kg
DIAGONAL_LOADS_KG = (0.0, 2.0)
_SPACING_M = 15 * MM
_STEP_M = 1 * MM
_DIAGONAL_Q_M = np.arange(20) * 10 * MM
_BUILTIN = ("machine.toml", "x_errors.csv", "z_errors.csv")
_SENSOR_MODEL = ("sensors_machine.toml", "sensors_x_errors.csv", "sensors_x_errors.json", "sensors_z_errors.csv",
                 "sensors_z_errors.json")


def _beam_point(module: VirtualModule, letter: str) -> np.ndarray:
    """Where the laser's beam meets the carriage: beside the scale's read head (as in the scale calibration)."""
    return np.asarray(module.heads[letter].scale_point_m) + INTERFEROMETER_BEAM_M


def _module(module: VirtualModule) -> VirtualModule:
    check_instance("module", module, VirtualModule, what="a VirtualModule")
    return module


def laser_run(module: VirtualModule, letter: str, *, runs: int = 5, targets: int = 11, seed: int = 0) -> dict[str, np.ndarray]:
    """Raw laser readings of a bidirectional ISO 230-2 test of one axis with air and material sensors.

    The reading is the beam point's true position (the axis' error motions moved to the beam by
    Abbe-Bryan) plus half the reversal against the direction of approach, a slow thermal drift
    and the repeatability scatter, stretched by the steel's expansion above 20 degC and by the
    refractive index of the air (Ciddor): ``reading = p20 (1 + alpha (t_material - 20)) n_air``,
    which ``axiscal positioning`` undoes.

    Parameters
    ----------
    module : VirtualModule
        The simulated module (its seed and load).
    letter : str
        ``"X"`` or ``"Z"``.
    runs : int, keyword-only
        Runs in each direction (default 5, the ISO 230-2 minimum).
    targets : int, keyword-only
        Target positions over the 190 mm stroke (default 11), uneven as ``axiscal plan`` makes them.
    seed : int, keyword-only
        Seed of the targets and the scatter.

    Returns
    -------
    dict of str to ndarray, shape (2 * runs * targets,)
        Columns ``target_mm, run, direction, actual_mm, air_temperature_c, pressure_pa,
        humidity_pct, material_temperature_c`` in measuring order (``direction`` holds "+" or "-").

    Raises
    ------
    AxiscalError
        For an axis the module does not have.

    Examples
    --------
    >>> run = laser_run(VirtualModule(seed=0), "X")
    >>> sorted(set(run["direction"].tolist()))
    ['+', '-']
    """
    _module(module)
    if not isinstance(letter, str) or letter not in module.heads:
        raise AxiscalError(f"the virtual module has no axis {letter!r}; use X or Z (letter)")
    runs = check_count("runs", runs)
    targets = check_count("targets", targets, minimum=2)
    seed = check_count("seed", seed, minimum=0)
    target_m = plan_targets(0.0, STROKE_M, targets, seed=seed)
    errors = module.true_errors(letter, target_m)
    index = "XYZ".index(letter)
    true_m = target_m + transfer_point(errors[:3].T, errors[3:].T, _beam_point(module, letter))[:, index]
    rng = np.random.default_rng([seed, 230, index])
    columns: dict[str, list] = {k: [] for k in ("target_mm", "run", "direction", "actual_mm", "air_temperature_c",
                                                "pressure_pa", "humidity_pct", "material_temperature_c")}
    for run in range(1, runs + 1):
        for direction, sign in (("+", -1.0), ("-", 1.0)):
            order = np.arange(target_m.size) if direction == "+" else np.arange(target_m.size)[::-1]
            position = true_m[order] + sign * REVERSAL_M[letter] / 2 + 0.05 * UM * (run - 1)
            position = position + rng.normal(0.0, REPEATABILITY_M, order.size)
            air_c = AIR["temperature_c"] + AIR["drift_c_per_run"] * (run - 1) + 0.02 * target_m[order] / STROKE_M
            pressure = np.full(order.size, AIR["pressure_pa"] - 5.0 * (run - 1))
            humidity = np.full(order.size, AIR["humidity_pct"])
            material_c = np.full(order.size, AIR["material_c"] + AIR["material_drift_c_per_run"] * (run - 1))
            n_air = refractive_index(air_c, pressure, humidity, VACUUM_WAVELENGTH_NM)
            reading = position * (1 + STEEL_EXPANSION_PER_K * (material_c - 20.0)) * n_air
            columns["target_mm"] += list(target_m[order] / MM)
            columns["run"] += [run] * order.size
            columns["direction"] += [direction] * order.size
            columns["actual_mm"] += list(reading / MM)
            columns["air_temperature_c"] += list(air_c)
            columns["pressure_pa"] += list(pressure)
            columns["humidity_pct"] += list(humidity)
            columns["material_temperature_c"] += list(material_c)
    return {k: np.asarray(v) for k, v in columns.items()}


def probe_readings(module: VirtualModule, *, seed: int = 0) -> dict[str, np.ndarray]:
    """Three probes on X's carriage reading a straightedge along Z: paper 001 eq (1).

    The slide motion S is the module's straightness EZX, its yaw gamma the carriage's turn in the
    XZ plane (``-EBX``), the workpiece profile R the straightedge's form :data:`STRAIGHTEDGE_M`;
    probes 15 mm apart, a reading every 1 mm over the stroke, probe noise as the virtual module's
    inductive probe.

    Parameters
    ----------
    module : VirtualModule
        The simulated module.
    seed : int, keyword-only
        Seed of the probe noise.

    Returns
    -------
    dict of str to ndarray
        Columns ``position_mm, a_um, b_um, c_um``.

    Examples
    --------
    >>> sorted(probe_readings(VirtualModule(seed=0)))
    ['a_um', 'b_um', 'c_um', 'position_mm']
    """
    _module(module)
    seed = check_count("seed", seed, minimum=0)
    length = STROKE_M + 2 * _SPACING_M

    def profile(x):
        return sum(a * np.sin(2 * np.pi * c * x / length + p) for a, c, p in STRAIGHTEDGE_M)

    readings = simulate_readings(
        np.arange(0.0, STROKE_M + _STEP_M / 2, _STEP_M),
        profile,
        lambda x: module.true_errors("X", x)[2],
        lambda x: -module.true_errors("X", x)[4],
        spacing_ab_m=_SPACING_M,
        spacing_bc_m=_SPACING_M,
        offsets_m=(0.4 * UM, -0.3 * UM, 0.2 * UM),
        noise_m=REFERENCE_NOISE["probe"] * UM,
        rng=np.random.default_rng([seed, 1]),
    )
    return {"position_mm": readings.position_m / MM, "a_um": readings.a_m / UM, "b_um": readings.b_m / UM,
            "c_um": readings.c_m / UM}


def _detrended(q_m: np.ndarray, value_m: np.ndarray) -> np.ndarray:
    """The curve about its least-squares line."""
    return value_m - np.polyval(np.polyfit(q_m, value_m, 1), q_m)


def squareness_runs(module: VirtualModule, *, points: int = 20, seed: int = 0) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """Two straightness runs against a laser beam and a pentaprism: X along Z, then Z along X.

    The runs carry the module's straightness EZX and EXZ about their least-squares lines, tilted so
    that the lines' included angle is 90 degrees minus the module's EB0Z (paper 002 eq 1; ISO 230-1
    sign), seen through a pentaprism that turns the beam by 90 degrees plus
    :data:`PRISM_DEVIATION_RAD` (eq 21), with an arbitrary alignment of the beam to X.

    Parameters
    ----------
    module : VirtualModule
        The simulated module (its squareness in ``module.machine``).
    points : int, keyword-only
        Readings per run over the stroke (default 20).
    seed : int, keyword-only
        Seed of the reading noise.

    Returns
    -------
    first, second : dict of str to ndarray
        Columns ``position_mm, deviation_um`` of the X run and the Z run.

    Examples
    --------
    >>> first, second = squareness_runs(VirtualModule(seed=0))
    >>> sorted(first)
    ['deviation_um', 'position_mm']
    """
    _module(module)
    points = check_count("points", points, minimum=2)
    seed = check_count("seed", seed, minimum=0)
    q = np.linspace(0.0, STROKE_M, points)
    rng = np.random.default_rng([seed, 2])
    included = -module.machine.squareness_rad["EB0Z"]  # opening beyond 90 degrees (paper 002 eq 1)
    alignment = 6.0 * ARCSEC  # the beam's tilt from X: it cancels in the included angle
    first = _detrended(q, module.true_errors("X", q)[2]) + np.tan(alignment) * q
    second = _detrended(q, module.true_errors("Z", q)[0]) + np.tan(-included - alignment - PRISM_DEVIATION_RAD) * q
    noise = REFERENCE_NOISE["interferometer"] * 20
    first, second = first + rng.normal(0.0, noise, q.size), second + rng.normal(0.0, noise, q.size)
    return ({"position_mm": q / MM, "deviation_um": first / UM}, {"position_mm": q / MM, "deviation_um": second / UM})


def diagonal_readings(module: VirtualModule) -> dict[str, np.ndarray]:
    """Laser interferometer readings on the XZ diagonal, 19 steps of 10 mm on each axis (paper 000 section 5).

    Parameters
    ----------
    module : VirtualModule
        The simulated module (its load).

    Returns
    -------
    dict of str to ndarray, shape (20,)
        Columns ``nominal_mm, measured_mm``, zeroed at X = Z = 0.

    Examples
    --------
    >>> float(diagonal_readings(VirtualModule(seed=0))["measured_mm"][0])
    0.0
    """
    _module(module)
    measured = module.laser_diagonal({"X": _DIAGONAL_Q_M, "Z": _DIAGONAL_Q_M.copy()})
    return {"nominal_mm": np.hypot(_DIAGONAL_Q_M, _DIAGONAL_Q_M) / MM, "measured_mm": measured / MM}


def _calibration_runs(module: VirtualModule) -> dict[str, np.ndarray]:
    """Calibration runs of the PSD and angle channels in one long table (reference in the channel's unit)."""
    runs = module.calibration_runs()
    channel, raw, reference = [], [], []
    for name, run in runs.items():
        if "reference" in run:
            channel += [name] * run["raw"].size
            raw += list(run["raw"])
            reference += list(run["reference"])
    return {"channel": np.asarray(channel), "raw": np.asarray(raw), "reference": np.asarray(reference)}


@dataclass(frozen=True)
class SimulatedCampaign:
    """A campaign folder :func:`write_campaign` wrote.

    Attributes
    ----------
    folder : Path
        The campaign folder (``campaign.toml`` and its data files).
    seed : int
        The seed of every simulation in it.
    files : tuple of str
        The files written, relative to the folder.
    """

    folder: Path
    seed: int
    files: tuple[str, ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "folder", check_path("folder", self.folder))
        check_count("seed", self.seed, minimum=0)
        if isinstance(self.files, (str, bytes)) or not all(isinstance(f, str) for f in self.files):
            raise AxiscalError(f"files must be a sequence of file names (str), not {self.files!r}"[:200])

    @property
    def toml(self) -> Path:
        """The campaign's ``campaign.toml``.

        Returns
        -------
        Path
        """
        return self.folder / "campaign.toml"


def _plain(path: Path, columns: dict[str, np.ndarray], formats: dict[str, str], *, kind: str, description: str, **meta) -> None:
    """A plain CSV (header first, fixed decimals) and its sidecar."""
    names = list(columns)
    lines = [",".join(names)]
    for row in zip(*(columns[n] for n in names)):
        lines.append(",".join(format(v, formats.get(n, "")) if formats.get(n) else str(v) for n, v in zip(names, row)))
    write_text(path, "\n".join(lines) + "\n")
    write_sidecar(path, kind=kind, description=description, simulated=True, made_by="axiscal demo", **meta)


def campaign_toml(seed: int = 0, *, budget: str | None = None, captured: bool = False) -> str:
    """The campaign.toml of the simulated campaign (template ``demo_campaign.toml.j2``).

    Parameters
    ----------
    seed : int
        Seed of the virtual module, named in the file.
    budget : str, optional, keyword-only
        File name of an uncertainty budget beside campaign.toml, named at its top.
    captured : bool, keyword-only
        The positioning runs were captured from laser recordings (notes say so).

    Returns
    -------
    str
    """
    seed = check_count("seed", seed, minimum=0)
    return render_template(
        "demo_campaign.toml.j2", keep_trailing_newline=True, seed=seed, wavelength_nm=VACUUM_WAVELENGTH_NM,
        prism_deviation_arcsec=PRISM_DEVIATION_RAD / ARCSEC, spacing_mm=_SPACING_M / MM, loads_kg=DIAGONAL_LOADS_KG,
        budget=budget, captured=captured,
    )


def write_campaign(folder: str | Path, *, seed: int = 0, laser_runs: bool = True) -> SimulatedCampaign:
    """Simulate the whole campaign on the virtual XZ module and write it as a campaign folder.

    Writes ``campaign.toml`` (from the template ``demo_campaign.toml.j2``), the module's model
    (``machine.toml`` and its error tables, the built-in XZ module), the 6-DOF sensor model with
    the calibration its simulated calibration runs give, the runs themselves, a 6-DOF recording
    along the diagonal with 2 kg on Z, the laser runs of X and Z, the probe readings, the two
    squareness runs and the diagonal readings unloaded and with 2 kg. Every file is written
    atomically; data CSVs are plain, with a JSON sidecar.

    Parameters
    ----------
    folder : str or Path
        The campaign folder (created if missing; files of the same names are replaced).
    seed : int, keyword-only
        Seed of the virtual module and of every simulated reading (default 0).
    laser_runs : bool, keyword-only
        Write the laser runs of X and Z (default); False leaves them to the caller (the demo
        captures them from the virtual machine's laser recording).

    Returns
    -------
    SimulatedCampaign

    Raises
    ------
    AxiscalError
        If the folder cannot be made or a file cannot be written.

    Examples
    --------
    >>> import tempfile
    >>> campaign = write_campaign(tempfile.mkdtemp())
    >>> campaign.toml.name
    'campaign.toml'
    """
    folder = check_path("folder", folder)
    seed = check_count("seed", seed, minimum=0)
    check_instance("laser_runs", laser_runs, bool)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise AxiscalError(f"cannot make the campaign folder: {exc.strerror or exc}", path=folder) from None
    data = resources.files("axiscal") / "data" / "xz_module"
    for name in _BUILTIN + _SENSOR_MODEL:
        write_text(folder / name, (data / name).read_text(encoding="utf-8"))
    module = VirtualModule(seed=seed)
    save_calibration(module.calibration, folder / "sensors_calibration.json")
    write_data_csv(folder / "sensor_calibration_runs.csv", _calibration_runs(module), kind="calibration run",
                   description="PSDs against an inductive probe, quadrant and roll detectors against an autocollimator "
                               "(paper 000 section 4.1); reference in the channel's unit")
    loaded = VirtualModule(seed=seed, load_kg=2.0)
    frames, _ = loaded.frames(np.arange(380) / 50.0, path="diagonal")
    write_data_csv(folder / "sixdof_diagonal_2kg.csv", frames, kind="raw frames",
                   description="raw frames of the virtual XZ module along the diagonal and back at 50 Hz, 2 kg on Z")
    for letter in ("X", "Z") if laser_runs else ():
        _plain(folder / f"positioning_{letter.lower()}.csv", laser_run(module, letter, seed=seed),
               {"target_mm": ".4f", "actual_mm": ".7f", "air_temperature_c": ".3f", "pressure_pa": ".1f",
                "humidity_pct": ".1f", "material_temperature_c": ".3f"},
               kind="positioning run", description=f"ISO 230-2 test of {letter}: raw laser readings with air and material sensors",
               units={"actual_mm": "mm, raw laser reading computed with the vacuum wavelength"},
               wavelength_nm=VACUUM_WAVELENGTH_NM, expansion_per_k=STEEL_EXPANSION_PER_K)
    _plain(folder / "probes_x.csv", probe_readings(module, seed=seed),
           {"position_mm": ".3f", "a_um": ".5f", "b_um": ".5f", "c_um": ".5f"}, kind="probe readings",
           description="three probes 15 mm apart on X's carriage reading a straightedge along Z (paper 001 eq 1)",
           spacing_mm=_SPACING_M / MM)
    first, second = squareness_runs(module, seed=seed)
    formats = {"position_mm": ".3f", "deviation_um": ".4f"}
    _plain(folder / "square_x.csv", first, formats, kind="straightness run",
           description="straightness of X along Z against the laser beam")
    _plain(folder / "square_z.csv", second, formats, kind="straightness run",
           description="straightness of Z along X against the beam turned by the pentaprism",
           prism_deviation_arcsec=PRISM_DEVIATION_RAD / ARCSEC)
    for load_kg in DIAGONAL_LOADS_KG:
        stops, _ = VirtualModule(seed=seed, load_kg=load_kg).frames_at({"X": _DIAGONAL_Q_M, "Z": _DIAGONAL_Q_M.copy()})
        write_data_csv(folder / f"sixdof_stops_{load_kg:g}kg.csv", stops, kind="raw frames",
                       description=f"raw frames of the virtual XZ module, one at each stop of the diagonal readings, "
                                   f"{load_kg:g} kg on Z")
        _plain(folder / f"diagonal_{load_kg:g}kg.csv", diagonal_readings(VirtualModule(seed=seed, load_kg=load_kg)),
               {"nominal_mm": ".6f", "measured_mm": ".6f"}, kind="diagonal readings",
               description=f"laser interferometer on the XZ diagonal, {load_kg:g} kg on Z", load_kg=load_kg)
    write_text(folder / "campaign.toml", campaign_toml(seed))
    files = tuple(sorted(p.name for p in folder.iterdir() if p.is_file()))
    return SimulatedCampaign(folder, seed, files)
