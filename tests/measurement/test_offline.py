"""The commands' library calls: plain CSVs with sidecars, SI results, one call per command."""

from __future__ import annotations

import json

import numpy as np
import pytest

from axiscal.errors import AxiscalError


def test_data_csvs_the_commands_write_are_plain_with_a_sidecar(examples, run_cli, tmp_path):
    import json

    import pandas

    frames = tmp_path / "frames.csv"
    results = tmp_path / "results.csv"
    laser = tmp_path / "laser.csv"
    for args in (
        ("simulate", "frames", "--rate", "100", "--duration", "0.5", "--truth", "-o", frames),
        ("measure", frames, "-o", results),
        ("simulate", "laser", "-o", laser),
    ):
        status, _, err = run_cli(*args)
        assert status == 0, err
    read = {path: pandas.read_csv(path) for path in (frames, results, laser)}
    assert list(read[frames].columns[:3]) == ["t_s", "x_cmd_mm", "x_scale_mm"] and "truth_ex_um" in read[frames].columns
    assert len(read[frames]) == 50
    assert list(read[results].columns[:2]) == ["t_s", "fault"] and {"ex_um", "e_um", "px_mm", "EXX_um", "ECZ_urad", "x_mm"} <= set(read[results].columns)
    assert list(read[laser].columns) == ["nominal_mm", "measured_mm"] and len(read[laser]) == 20
    assert json.loads(results.with_suffix(".json").read_text())["fault_bits"]["4"] == "position outside the error model"
    assert json.loads(frames.with_suffix(".json").read_text())["kind"] == "raw frames"
    assert json.loads(laser.with_suffix(".json").read_text())["kind"] == "interferometer readings"


def test_measure_file_results_are_si(examples):
    from axiscal.measurement.offline import measure_file

    result = measure_file(examples / "xz_module" / "sensors_frames.csv")
    shown = result.columns()
    good = result.fault == 0
    np.testing.assert_allclose(result.results["ex_m"][good] / 1e-6, shown["ex_um"][good], rtol=1e-12)
    np.testing.assert_allclose(result.results["px_m"][good] / 1e-3, shown["px_mm"][good], rtol=1e-12)
    np.testing.assert_allclose(result.results["EAX_rad"][good] / 1e-6, shown["EAX_urad"][good], rtol=1e-12)
    assert result.summary()["faulty_frames"] == 2


def test_every_command_is_one_call(examples, tmp_path):
    from axiscal.instruments.calibration import load_calibration
    from axiscal.measurement import offline
    from axiscal.units import MM, UM

    folder = examples / "xz_module"
    report = offline.calibrate_sensitivity(folder / "sensors_psd_run.csv", "x_psd_y_um", output=tmp_path / "cal.json")
    assert report["points"] == 21 and "x_psd_y_um" in load_calibration(tmp_path / "cal.json").channels
    moved = offline.calibrate_sensitivity(folder / "sensors_scale_run.csv", "x_scale_mm", reference_offset_m=(0.0, -45 * MM, -20 * MM))
    assert moved["residual_max_mm"] < 0.5e-3
    mirror = offline.calibrate_mirror(folder / "sensors_mirror_run.csv", "x")
    assert mirror["axis"] == "X" and len(mirror["cv_rms_arcsec"]) > 1
    frames = offline.simulate_frames(rate_hz=50.0, duration_s=1.0)
    assert frames.rows == 50 and frames.text.startswith("t_s,x_cmd_mm,")
    laser = offline.simulate_laser(steps=3)
    assert laser.rows == 4 and laser.text.splitlines()[0] == "nominal_mm,measured_mm"
    diagonal = offline.run_diagonal_experiment(load_kg=2.0)
    assert round(diagonal.experiment.before_max_m / UM) == 56 and diagonal.to_dict()["paper_um"] == {"before": 56.0, "after": 14.0}
    assert "paper 000: 56 -> 14 um" in diagonal.text()
    with pytest.raises(AxiscalError, match="allowed 1 to"):
        offline.simulate_frames(rate_hz=1e9, duration_s=1.0)
    with pytest.raises(AxiscalError, match="unknown path"):
        offline.simulate_frames(path="circle")
    with pytest.raises(AxiscalError, match="must not be negative"):
        offline.run_diagonal_experiment(load_kg=-1.0)


def test_a_record_without_its_sidecar_is_still_known_by_its_columns(tmp_path):
    from axiscal.measurement.offline import is_live_record

    plain = tmp_path / "frames.csv"
    plain.write_text("t_s,a\n0,1\n")
    assert not is_live_record(plain, ["t_s", "a"])
    assert is_live_record(plain, ["t_s", "a", "fault", "ex_um", "e_um"])
    (tmp_path / "frames.json").write_text('{"kind": "live record"}')
    assert is_live_record(plain, ["t_s", "a"])


def test_the_example_data_are_plain_csvs_pandas_reads_with_no_options(examples):
    import json

    import pandas

    files = sorted((examples / "xz_module").glob("sensors_*.csv"))
    assert len(files) == 7
    for path in files:
        frame = pandas.read_csv(path)
        assert len(frame) > 0 and not any(str(c).startswith("#") for c in frame.columns), path
        assert json.loads(path.with_suffix(".json").read_text())["file"] == path.name
    frames = pandas.read_csv(examples / "xz_module" / "sensors_frames.csv")
    assert len(frames) == 200 and frames["t_s"].iloc[-1] == pytest.approx(199 / 50.0)


def test_fit_uncertainties_are_the_least_squares_standard_errors():
    """Reference: scipy.stats.linregress's standard errors of slope and intercept."""
    from scipy.stats import linregress

    from axiscal.measurement.calibrate import _line_fit_uncertainty

    rng = np.random.default_rng(3)
    x = np.linspace(-80.0, 90.0, 17)
    y = 0.97 * x + 4.0 + rng.normal(0.0, 0.3, x.size)
    fit = linregress(x, y)
    rms = float(np.sqrt(np.mean((y - (fit.slope * x + fit.intercept)) ** 2)))
    u_gain, u_offset = _line_fit_uncertainty(x, rms)
    assert u_gain == pytest.approx(fit.stderr, rel=1e-12) and u_offset == pytest.approx(fit.intercept_stderr, rel=1e-12)


def test_calibrate_prints_the_digits_that_mean_something_and_json_keeps_all(examples, run_cli):
    run = examples / "xz_module" / "sensors_psd_run.csv"
    status, out, err = run_cli("calibrate", "sensitivity", run, "--channel", "x_psd_y_um")
    assert status == 0, err
    status, js, err = run_cli("calibrate", "sensitivity", run, "--channel", "x_psd_y_um", "--json")
    report = json.loads(js)
    shown = dict(line.split(": ", 1) for line in out.splitlines())
    assert shown["gain"] == "0.95499" and shown["gain_u"] == "0.00073"  # the gain to the 2nd digit of its uncertainty
    assert shown["offset_um"] == "-19.379" and shown["residual_rms_um"] == "0.18"
    assert report["gain"] == pytest.approx(0.95499, abs=5e-6) and len(repr(report["gain"])) > 12  # --json: full precision
    for key, value in shown.items():
        if key == "channel":
            continue
        digits = value.lstrip("-").replace(".", "").lstrip("0")
        assert len(digits) <= 7, value  # never the 16 digits of a float
    status, out, err = run_cli("calibrate", "mirror", examples / "xz_module" / "sensors_mirror_run.csv", "--axis", "x")
    assert status == 0 and "residual_rms_arcsec: 0.25\n" in out
