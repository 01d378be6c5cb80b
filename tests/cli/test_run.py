"""`axiscal run` at its boundaries: every flag refused in one line in its own unit, every reading held against its target."""

from __future__ import annotations

import pytest

from axiscal.positioning.plan import plan_test, write_plan


@pytest.fixture(scope="module")
def plan_csv(tmp_path_factory):
    path = tmp_path_factory.mktemp("plan") / "plan.csv"
    write_plan(plan_test(0.020, 0.120, 5, runs=1, overrun_m=0.002, seed=2), path)
    return path


@pytest.mark.parametrize(("args", "flag"), [
    (("--controller", "moonraker:not a url"), "moonraker:URL"),  # was http.client.InvalidURL
    (("--window-s", "1e300"), "--window-s"),  # was OverflowError in a wait
    (("--seed", "-1"), "--seed"),  # was ValueError from NumPy
    (("--wavelength-nm", "0"), "--wavelength-nm"),  # the simulator's thread died of ZeroDivisionError first
    (("--feed-mm-min", "1e300"), "--feed-mm-min"),  # was driven
    (("--feed-mm-min", "1000000", "--dry-run"), "--feed-mm-min"),  # was G1 X0.0000 F1e+06
    (("--stability-um", "-1"), "--stability-um"),  # said "of m"
    (("--stability-um", "1e300"), "--stability-um"),
    (("--offset-mm", "1e300"), "--offset-mm"),
    (("--counts-per-mm", "1e300", "--source", "sim:touchdro"), "--counts-per-mm"),
    (("--tolerance-mm", "0"), "--tolerance-mm"),
    (("--rate-hz", "1e300"), "--rate-hz"),
])
def test_a_flag_out_of_its_range_is_one_line_naming_it(run_cli, plan_csv, tmp_path, args, flag):
    base = {"--controller": "sim", "--source": "sim:umd"}
    given = dict(zip(args[::2], args[1::2])) if "--dry-run" not in args else {}
    argv = ["run", plan_csv, "-o", tmp_path / "run.csv"]
    for name, value in base.items():
        argv += [name, given.get(name, value)]
    argv += [a for i, a in enumerate(args) if not (a in base or (i and args[i - 1] in base))]
    status, out, err = run_cli(*argv)
    assert status == 2 and err.count("\n") == 1 and err.startswith("axiscal: error: ") and flag in err, err
    assert "Traceback" not in err and " of m," not in err and not (tmp_path / "run.csv").exists()


def test_the_dry_run_writes_the_words_a_control_reads(run_cli, plan_csv):
    status, out, err = run_cli("run", plan_csv, "--controller", "sim", "--source", "sim", "--dry-run", "--feed-mm-min", "100000")
    assert status == 0 and "step 2: G1 X20.0000 F100000  (reading)" in out and "e+" not in out


@pytest.mark.parametrize(("args", "reads"), [(("--offset-mm", "100"), "-80.01"),  # wrote a deviation of -100012.6 um
                                             (("--source", "sim:sylvac", "--unit", "in"), "507.6")])  # wrote +121669.8 um
def test_a_reading_not_near_its_target_stops_the_run_naming_the_step_and_the_flags(run_cli, plan_csv, tmp_path, args, reads):
    argv = ["run", plan_csv, "--controller", "sim", "-o", tmp_path / "run.csv", "--dwell-s", "0.3", "--window-s", "0.1", *args]
    if "--source" not in args:
        argv += ["--source", "sim:umd"]
    status, out, err = run_cli(*argv)
    assert status == 2 and err.count("\n") == 1, err
    assert err.startswith("axiscal: error: step 2 (target 20.000 mm, run 1, +): the instrument reads " + reads)
    assert "--offset-mm" in err and "--tolerance-mm 0.5 mm" in err and not (tmp_path / "run.csv").exists()


def test_on_the_fly_says_the_speed_it_holds_to_and_warns_above_it(run_cli, tmp_path):
    plan_csv = tmp_path / "plan.csv"
    write_plan(plan_test(0.020, 0.120, 5, runs=1, overrun_m=0.015, seed=2), plan_csv)  # room to reach the feed
    status, out, err = run_cli("run", plan_csv, "--controller", "sim", "--source", "sim:umd", "--on-the-fly",
                               "--feed-mm-min", "8000", "-o", tmp_path / "fly.csv", "--json")
    assert status == 0, err
    assert "within 1 um of stop and go up to 4000 mm/min (measured on the virtual controller)" in err
    assert "axiscal: warning: targets crossed at up to" in err and "above the 4000 mm/min" in err
    import json

    payload = json.loads(out)
    assert payload["agreement_up_to_mm_min"] == pytest.approx(4000) and payload["warning"].startswith("targets crossed")


def test_no_warning_below_the_speed():
    import numpy as np

    from axiscal.capture.fly_drive import FLY_SPEED_LIMIT_M_S, FlyFiles

    class _Result:
        speed_m_s = np.array([FLY_SPEED_LIMIT_M_S, -0.5 * FLY_SPEED_LIMIT_M_S])

    files = FlyFiles(_Result(), None, None, None)
    assert files.warning is None and "up to 4000 mm/min" in files.agreement
    _Result.speed_m_s = np.array([1.01 * FLY_SPEED_LIMIT_M_S])
    assert "4040 mm/min, above the 4000 mm/min" in files.warning
