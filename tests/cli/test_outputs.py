"""Every command that writes a file makes the folders its output path names (as ``mkdir -p`` would)."""

from __future__ import annotations

from pathlib import Path

import click
import pytest

from cli_commands import leaf_commands

OUT = "no/such/dir"
"""Stands for the folder a test asks a command to write into, which does not exist."""

# (command path, the writing option, the whole command line); OUT is replaced by a missing folder in tmp_path
WRITES = [
    (("ballbar",), "--plot", ["ballbar", "{ex}/ballbar/ballbar_run.csv", "--radius-mm", "100", "--plane", "XY", "--plot", "{out}/polar.png"]),
    (("calibrate", "mirror"), "--output", ["calibrate", "mirror", "{ex}/xz_module/sensors_mirror_run.csv", "--axis", "x", "-o", "{out}/cal.json"]),
    (("calibrate", "sensitivity"), "--output", ["calibrate", "sensitivity", "{ex}/xz_module/sensors_psd_run.csv", "--channel", "x_psd_y_um", "-o", "{out}/cal.json"]),
    (("cmm", "acceptance"), "--plot", ["cmm", "acceptance", "{ex}/cmm/e0_gauge_blocks.csv", "--mpe-a-um", "1.8", "--mpe-k", "300", "--plot", "{out}/e0.png"]),
    (("cmm", "probing"), "--plot", ["cmm", "probing", "{ex}/cmm/sphere_single.csv", "--diameter-mm", "25.00018", "--plot", "{out}/p.png"]),
    (("cmm", "compensate"), "--output", ["cmm", "compensate", "--squareness-arcmin", "8.05,27.1,-16.6", "{ex}/cmm_points.csv", "-o", "{out}/c.csv"]),
    (("compensate",), "--output", ["compensate", "{ex}/positioning_run.csv", "--format", "linuxcnc", "-o", "{out}/x.comp"]),
    (("dcc", "sign"), "--output", ["dcc", "sign", "{tmp}/dcc.xml", "--key", "{tmp}/key.pem", "--cert", "{tmp}/cert.pem", "-o", "{out}/s.xml"]),
    (("diagonal",), "--output", ["diagonal", "--machine", "{ex}/xz_module/machine.toml", "--from", "X=0,Z=0", "--to", "X=190,Z=190", "-o", "{out}/d.csv"]),
    (("diagonal",), "--plot", ["diagonal", "--machine", "{ex}/xz_module/machine.toml", "--from", "X=0,Z=0", "--to", "X=190,Z=190", "--plot", "{out}/d.png"]),
    (("experiment", "diagonal"), "--plot", ["experiment", "diagonal", "--samples", "1", "--plot", "{out}/e.png"]),
    (("export", "sag"), "--output", ["export", "sag", "{ex}/squareness_y.csv", "--controller", "heidenhain", "--base-axis", "Y", "--compensation-axis", "X", "-o", "{out}/s.COM"]),
    (("export", "screwmap"), "--output", ["export", "screwmap", "{ex}/positioning_run.csv", "--controller", "mach4", "-o", "{out}/m.txt"]),
    (("import", "map"), "--output", ["import", "map", "{ex}/imports/runs_per_column.toml", "{ex}/imports/runs_per_column.csv", "-o", "{out}/run.csv"]),
    (("import", "rtx"), "--output", ["import", "rtx", "{ex}/imports/capture.rtx", "--unit", "mm", "-o", "{out}/c.csv"]),
    (("inverse",), "--output", ["inverse", "--machine", "{ex}/xfyz_machine/machine.toml", "--points", "{tmp}/points.csv", "-o", "{out}/i.csv"]),
    (("measure",), "--output", ["measure", "{ex}/xz_module/sensors_frames.csv", "--machine", "{ex}/xz_module/sensors_machine.toml", "-o", "{out}/r.csv"]),
    (("optics", "pentaprism"), "--plot", ["optics", "pentaprism", "--steps", "3", "--plot", "{out}/p.png"]),
    (("plan",), "--output", ["plan", "--start-mm", "0", "--end-mm", "100", "--targets", "6", "-o", "{out}/p.csv"]),
    (("plan",), "--gcode", ["plan", "--start-mm", "0", "--end-mm", "100", "--targets", "6", "--gcode", "{out}/p.gcode"]),
    (("positioning",), "--plot", ["positioning", "{ex}/positioning_run.csv", "--plot", "{out}/p.png"]),
    (("report",), "--output", ["report", "{ex}/campaign", "-o", "{out}/report"]),
    (("separate",), "--output", ["separate", "{ex}/probe_readings.csv", "--spacing-mm", "15", "-o", "{out}/s.csv"]),
    (("separate",), "--plot", ["separate", "{ex}/probe_readings.csv", "--spacing-mm", "15", "--plot", "{out}/s.png"]),
    (("simulate", "ballbar"), "--output", ["simulate", "ballbar", "--step-deg", "1", "-o", "{out}/b.csv"]),
    (("simulate", "frames"), "--output", ["simulate", "frames", "--duration", "0.01", "-o", "{out}/f.csv"]),
    (("simulate", "laser"), "--output", ["simulate", "laser", "--steps", "3", "-o", "{out}/l.csv"]),
    (("simulate", "probes"), "--output", ["simulate", "probes", "--profile", "{ex}/separation_profile.csv", "--motion", "{ex}/separation_motion.csv", "--spacing-mm", "15", "--step-mm", "1", "-o", "{out}/p.csv"]),
    (("simulate-probes",), "--output", ["simulate-probes", "--profile", "{ex}/separation_profile.csv", "--motion", "{ex}/separation_motion.csv", "--spacing-mm", "15", "--step-mm", "1", "-o", "{out}/p.csv"]),
    (("squareness",), "--plot", ["squareness", "--first", "{ex}/squareness_x.csv", "--second", "{ex}/squareness_y.csv", "--plot", "{out}/q.png"]),
    (("straightness",), "--plot", ["straightness", "{ex}/straightness_profile.csv", "--plot", "{out}/s.png"]),
    (("uncertainty", "volumetric"), "--output", ["uncertainty", "volumetric", "--machine", "{ex}/xfyz_machine_u/machine.toml", "--grid", "X=0:800:400,Y=0:500:500,Z=0", "-o", "{out}/u.csv"]),
    (("uncertainty", "volumetric"), "--plot", ["uncertainty", "volumetric", "--machine", "{ex}/xfyz_machine_u/machine.toml", "--grid", "X=0:800:400,Y=0:500:500,Z=0", "--plot", "{out}/u.png"]),
    (("volumetric",), "--output", ["volumetric", "--machine", "{ex}/xfyz_machine/machine.toml", "--grid", "X=0:600:300,Y=0:400:400,Z=0:300:300", "-o", "{out}/v.csv"]),
    (("volumetric",), "--plot", ["volumetric", "--machine", "{ex}/xfyz_machine/machine.toml", "--grid", "X=0:600:300,Y=0:400:400,Z=0:300:300", "--plot", "{out}/v.png"]),
    (("capture",), "--output", ["capture", "{ex}/capture/plan_x.csv", "--from", "{ex}/capture/recording_x.csv", "-o", "{out}/run.csv"]),
    (("simulate", "capture"), "--output", ["simulate", "capture", "{ex}/capture/x.ngc", "--machine", "{ex}/xz_module/machine.toml", "--axis", "X", "--rate-hz", "50", "-o", "{out}/rec.csv"]),
    (("levels",), "--output", ["levels", "{ex}/levels/levels_run.csv", "--foot-mm", "100", "-o", "{out}/p.csv"]),
    (("levels",), "--plot", ["levels", "{ex}/levels/levels_run.csv", "--foot-mm", "100", "--plot", "{out}/p.png"]),
    (("flatness",), "--output", ["flatness", "{ex}/flatness/union_jack_levels.toml", "-o", "{out}/f.csv"]),
    (("flatness",), "--plot", ["flatness", "{ex}/flatness/union_jack_levels.toml", "--plot", "{out}/f.png"]),
    (("thermal", "etve"), "--plot", ["thermal", "etve", "{ex}/thermal/etve_run.csv", "--plot", "{out}/t.png"]),
    (("thermal", "drift"), "--plot", ["thermal", "drift", "{ex}/thermal/drift_run.csv", "--plot", "{out}/t.png"]),
    (("identify",), "--output", ["identify", "{ex}/identification/start/machine.toml", "{ex}/identification/plate_xy.toml", "--model", "poly:1", "-o", "{out}/id"]),
    (("precompensate",), "--output", ["precompensate", "{ex}/precompensation/part.ngc", "--machine", "{ex}/xfyz_machine/machine.toml", "--dialect", "linuxcnc", "-o", "{out}/x.ngc"]),
    (("export", "grid"), "--output", ["export", "grid", "--machine", "{ex}/xfyz_machine/machine.toml", "--grid", "X=50:750:350,Y=50:450:400,Z=50:350:300", "-o", "{out}/g.csv"]),
    (("export", "grid"), "--output", ["export", "grid", "--machine", "{ex}/xfyz_machine/machine.toml", "--grid", "X=50:750:350,Y=50:450:400,Z=50:350:300", "--format", "isg", "-o", "{out}/volcomp.csv"]),
    (("history", "export"), "--output", ["history", "export", "M", "--db", "{tmp}/h.db", "-o", "{out}/h.csv"]),
    (("history", "trend"), "--plot", ["history", "trend", "M", "--figure", "positioning.X.E", "--db", "{tmp}/h.db", "--plot", "{out}/t.png"]),
    (("fleet", "report"), "--output", ["fleet", "report", "{tmp}/fleet", "--scheduler", "threads", "-o", "{out}/fleet"]),
    (("dynamics",), "--plot", ["dynamics", "{ex}/capture/recording_x.csv", "--plot", "{out}/d.png"]),
    (("periodic",), "--plot", ["periodic", "{ex}/dynamics/step_cycle_run.csv", "--plot", "{out}/p.png"]),
    (("on-the-fly",), "--output", ["on-the-fly", "{ex}/dynamics/fly_plan.csv", "--from", "{ex}/dynamics/fly_recording.csv", "-o", "{out}/r.csv"]),
    (("on-the-fly",), "--plot", ["on-the-fly", "{ex}/dynamics/fly_plan.csv", "--from", "{ex}/dynamics/fly_recording.csv", "-o", "{tmp}/r.csv", "--plot", "{out}/f.png"]),
    (("live",), "--record", ["live", "--no-server", "--no-pace", "--duration", "0.05", "--record", "{out}/live.csv"]),
    (("run",), "--output", ["run", "{tmp}/plan.csv", "--controller", "sim", "--source", "sim:umd", "--feed-mm-min", "20000",
                            "--dwell-s", "0.25", "--window-s", "0.1", "-o", "{out}/run.csv"]),
    (("cycle",), "--output", ["cycle", "{tmp}/plan.csv", "--controller", "sim", "--source", "sim:umd", "--feed-mm-min", "20000",
                              "--dwell-s", "0.25", "--window-s", "0.1", "-o", "{out}/cycle"]),
]
WRITING_FLAGS = ("--output", "--plot", "--gcode", "--record")
# writing options another test already drives into a missing folder (the demo takes seconds: run once)
COVERED_ELSEWHERE = {(("demo",), "--output"): "tests/cli/test_demo.py::test_demo_writes_the_campaign_and_its_report"}


def written_by_commands() -> set[tuple[tuple[str, ...], str]]:
    return {(path, flag) for path, command in leaf_commands() for param in command.params
            if isinstance(param, click.Option) for flag in param.opts if flag in WRITING_FLAGS}


def test_every_writing_option_is_tried():
    assert written_by_commands() == {(path, flag) for path, flag, _ in WRITES} | set(COVERED_ELSEWHERE)


@pytest.mark.parametrize("path, flag, argv", [pytest.param(*w, id=" ".join(w[0]) + " " + w[1]) for w in WRITES])
def test_a_command_makes_the_folders_of_its_output(run_cli, examples, tmp_path, path, flag, argv):
    (tmp_path / "points.csv").write_text("x_mm,y_mm,z_mm\n-200,100,-100\n")
    if path[0] == "history":  # a database holding three campaigns of machine M
        from axiscal.history import Drift, add_results, drifting_results, write_results

        payloads = drifting_results({"positioning.X.E": Drift(5.0, 1.0, 1.0, 20.0)}, machine="M", campaigns=3)
        add_results(write_results(tmp_path / "m", payloads), url=str(tmp_path / "h.db"))
    if path[0] == "dcc":  # a DCC and a signer's key and certificate
        _signer(tmp_path)
    if path[0] in ("run", "cycle"):  # a short plan for the virtual controller
        from axiscal.positioning.plan import plan_test, write_plan

        write_plan(plan_test(0.010, 0.030, 5, runs=1, seed=3), tmp_path / "plan.csv")  # short moves: what is checked is the folder
    if path[0] == "fleet":  # a folder of one campaign
        from axiscal.fleet.generate import generated_fleet

        generated_fleet(tmp_path / "fleet", machines=1, campaigns=1)
    out = tmp_path / OUT
    line = [a.format(ex=examples, tmp=tmp_path, out=out) for a in argv]
    status, _, err = run_cli(*line)
    assert status == 0, err
    target = next(a for a in line if a.startswith(str(out)))
    assert Path(target).exists()


def test_a_folder_that_cannot_be_made_is_one_line(run_cli, examples, tmp_path):
    (tmp_path / "file").write_text("a file where a folder would go\n")
    target = tmp_path / "file" / "x.txt"
    status, out, err = run_cli("compensate", examples / "positioning_run.csv", "--format", "linuxcnc", "-o", target)
    assert status == 2 and out == "" and err.startswith(f"axiscal: error: {target}: cannot write this file") and err.count("\n") == 1


def _signer(folder: Path) -> None:
    import datetime as dt

    from cryptography import x509
    from cryptography.hazmat.primitives import hashes, serialization
    from cryptography.hazmat.primitives.asymmetric import ec
    from cryptography.x509.oid import NameOID

    key = ec.generate_private_key(ec.SECP256R1())
    name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "Lab")])
    start = dt.datetime(2026, 1, 1, tzinfo=dt.timezone.utc)
    cert = (x509.CertificateBuilder().subject_name(name).issuer_name(name).public_key(key.public_key()).serial_number(1)
            .not_valid_before(start).not_valid_after(start + dt.timedelta(days=30)).sign(key, hashes.SHA256()))
    (folder / "key.pem").write_bytes(key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                                       serialization.NoEncryption()))
    (folder / "cert.pem").write_bytes(cert.public_bytes(serialization.Encoding.PEM))
    (folder / "dcc.xml").write_text("<dcc:digitalCalibrationCertificate xmlns:dcc='https://ptb.de/dcc' schemaVersion='3.2.0'>"
                                    "<dcc:administrativeData/><dcc:measurementResults/></dcc:digitalCalibrationCertificate>")
