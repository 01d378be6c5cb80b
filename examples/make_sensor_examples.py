"""Write the measurement-system examples in examples/xz_module/sensors_* (run from the repository root).

    python examples/make_sensor_examples.py

Everything comes from the virtual XZ module of paper 000 (axiscal.measurement.virtual, seed 0, no load):
its machine description with the sensor geometry, its error tables (the truth, no load), the
calibration its simulated calibration runs give, the runs themselves (so `axiscal calibrate` can be
tried on them), and a short recording of raw frames along the diagonal with two faulty frames.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.measurement.offline import write_data_csv
from axiscal.instruments.calibration import save_calibration
from axiscal.io.atomic import write_text
from axiscal.measurement.virtual import INTERFEROMETER_BEAM_M, STROKE_M, VirtualModule
from axiscal.units import ARCSEC, MM, UM, URAD

OUT = Path(__file__).resolve().parent.parent / "src" / "axiscal" / "data" / "xz_module"


def _mm(point) -> str:
    return "[" + ", ".join(f"{c / MM:.1f}" for c in point) + "]"


def _signed(head, component) -> str:
    names = ("EXX", "EYX", "EZX", "EAX", "EBX", "ECX") if head.letter == "X" else ("EXZ", "EYZ", "EZZ", "EAZ", "EBZ", "ECZ")
    return ("-" if component.sign < 0 else "") + names[component.index]


def machine_toml(module: VirtualModule) -> str:
    lines = [
        "# The virtual XZ module of paper 000 with its 6-DOF sensor heads (written by examples/make_sensor_examples.py).",
        "# Error tables: the module's true error motions (no load); the measurement system uses them only",
        "# for the travel. Sensor sections: docs/formats.md, \"Sensor geometry\".",
        'name = "virtual XZ module (paper 000)"',
        'chain = "FXZ"',
        "tool_mm = [0.0, -40.0, 0.0]",
        "",
    ]
    for letter in ("X", "Z"):
        head = module.heads[letter]
        lines += [f"[axes.{letter}]", f'errors = "sensors_{letter.lower()}_errors.csv"', 'interpolation = "cubic"']
        if letter == "Z":
            lines.append("origin_mm = [0.0, 0.0, 50.0]")
        lines += [
            "",
            f"[axes.{letter}.sensors]",
            f'prefix = "{head.prefix}"',
            f"scale_point_mm = {_mm(head.scale_point_m)}   # read head of the scale (Abbe point), carriage frame",
            f"psd_point_mm = {_mm(head.psd_point_m)}     # PSD spot (Bryan point)",
            f"qd_focal_mm = {head.qd_focal_m / MM:.1f}           # f1 of eq (2)",
            f"roll_focal_mm = {head.roll_focal_m / MM:.1f}          # f2 of eq (3)",
            f'qd_u = "{_signed(head, head.qd_u)}"',
            f'qd_v = "{_signed(head, head.qd_v)}"',
            f'roll = "{_signed(head, head.roll)}"',
            f"psd_range_um = {head.psd_range_m / UM:.1f}",
            f"qd_range_um = {head.qd_range_m / UM:.1f}",
            f"roll_range_um = {head.roll_range_m / UM:.1f}",
            'calibration = "sensors_calibration.json"',
            "",
        ]
    lines += ["[squareness]", "EB0Z_arcsec = -42.4"]
    return "\n".join(lines) + "\n"


def main() -> None:
    module = VirtualModule(seed=0)
    write_text(OUT / "sensors_machine.toml", machine_toml(module))
    q = np.linspace(0.0, STROKE_M, 39)
    for letter in ("X", "Z"):
        table = module.machine.table(letter)
        columns = {"position_mm": q / MM}
        for row, name in enumerate(table.names):
            columns[f"{name}_{'um' if row < 3 else 'urad'}"] = table.evaluate(q)[row] / (UM if row < 3 else URAD)
        write_data_csv(OUT / f"sensors_{letter.lower()}_errors.csv", columns, kind="error table", description="true error motions of the virtual XZ module, no load")
    save_calibration(module.calibration, OUT / "sensors_calibration.json")

    runs = module.calibration_runs()
    write_data_csv(
        OUT / "sensors_psd_run.csv",
        {"x_psd_y_um": runs["x_psd_y_um"]["raw"], "reference_um": runs["x_psd_y_um"]["reference"]},
        kind="calibration run",
        description="PSD x_psd_y_um displaced against an inductive probe (paper 000 section 4.1.1)",
    )
    head = module.heads["X"]
    angle = runs["x_qd_u_um"]["reference"] * UM / head.qd_focal_m * head.qd_u.sign
    write_data_csv(
        OUT / "sensors_qd_run.csv",
        {"x_qd_u_um": runs["x_qd_u_um"]["raw"], "reference_arcsec": angle / ARCSEC},
        kind="calibration run",
        description="quadrant detector x_qd_u_um tilted against an autocollimator (section 4.1.2)",
    )
    scale = runs["x_scale_mm"]
    offset = -INTERFEROMETER_BEAM_M / MM + 0.0
    write_data_csv(
        OUT / "sensors_scale_run.csv",
        {
            "position_mm": scale["position_m"] / MM,
            "x_scale_mm": scale["raw"],
            "reference_mm": scale["interferometer_m"] / MM,
            "EAX_urad": scale["eps_rad"][:, 0] / URAD,
            "EBX_urad": scale["eps_rad"][:, 1] / URAD,
            "ECX_urad": scale["eps_rad"][:, 2] / URAD,
        },
        kind="calibration run",
        description=(
            "scale x_scale_mm against a laser interferometer whose beam is off the read head (section 4.2.1); "
            f"read head minus beam = {offset[0]:g},{offset[1]:g},{offset[2]:g} mm (--reference-offset-mm); angles from an autocollimator"
        ),
    )
    mirror = runs["X_mirror"]
    write_data_csv(
        OUT / "sensors_mirror_run.csv",
        {"position_mm": mirror["position_m"] / MM, "x_roll_um": mirror["raw"], "level_arcsec": mirror["level_rad"] / ARCSEC},
        kind="calibration run",
        description="roll detector x_roll_um and a level along X: the plane mirror's form error (eq 11)",
    )

    frames, _ = module.frames(np.arange(200) / 50.0, path="diagonal")
    frames["x_psd_y_um"][50] = np.nan
    frames["z_qd_u_um"][120] = 9999.0
    write_data_csv(
        OUT / "sensors_frames.csv",
        frames,
        kind="raw frames",
        description="raw frames of the virtual XZ module along the diagonal at 50 Hz (seed 0); frame 50 lacks x_psd_y_um, frame 120 has z_qd_u_um out of range",
    )


if __name__ == "__main__":
    main()
