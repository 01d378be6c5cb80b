"""The boundaries of ``plan``, ``run`` (its dry run: nothing moves) and ``compensate``, fed malformed numbers.

Each flag that carries a number is given the values a hand or a script gets wrong: 0, a negative, a huge
one, 1e300, nan, inf, a word. A command either runs (status 0, and then every G-code word it prints is fixed
point with at most five whole digits) or refuses in one line, ``axiscal: error: ...``, status 2,
no traceback. Nothing else is acceptable.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from axiscal.positioning.plan import plan_test, write_plan

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
VALUES = ("0", "-1", "1e6", "1e300", "nan", "inf", "-inf", "ten")

#: command -> (its arguments, the number flags mutated)
PLAN = ("plan", "--start-mm", "0", "--end-mm", "100", "--targets", "5", "--seed", "1", "--gcode", "{out}")
FLAGS = {
    "plan": (PLAN, ("--start-mm", "--end-mm", "--overrun-mm", "--feed-mm-min", "--dwell-s", "--targets", "--runs", "--seed")),
    "plan --step-cycle": (("plan", "--step-cycle", "--start-mm", "0", "--period-mm", "5", "--gcode", "{out}"),
                          ("--start-mm", "--period-mm", "--periods", "--steps-per-period", "--overrun-mm", "--feed-mm-min")),
    "run --dry-run": (("run", "{plan}", "--controller", "sim", "--source", "sim", "--dry-run"), ("--feed-mm-min",)),
    "compensate": (("compensate", str(EXAMPLES / "positioning_run.csv"), "--format", "linuxcnc", "-o", "{out}"),
                   ("--max-correction-mm", "--max-correction-deg")),
}
CASES = [(command, flag, value) for command, (_, flags) in FLAGS.items() for flag in flags for value in VALUES]
#: a G-code word of a position or a feed as every control reads it
WORD = re.compile(r"\b[XF]-?\d{1,6}(\.\d*)?\b")


@pytest.fixture(scope="module")
def plan_csv(tmp_path_factory):
    path = tmp_path_factory.mktemp("plan") / "plan.csv"
    write_plan(plan_test(0.020, 0.120, 5, runs=1, overrun_m=0.002, seed=2), path)
    return path


@pytest.mark.parametrize(("command", "flag", "value"), CASES, ids=[f"{c}{f}={v}" for c, f, v in CASES])
def test_a_malformed_number_runs_cleanly_or_is_refused_in_one_line(run_cli, plan_csv, tmp_path, command, flag, value):
    argv, _ = FLAGS[command]
    out = tmp_path / "out.txt"
    args = [a.format(out=out, plan=plan_csv) for a in argv]
    if flag in args:
        args[args.index(flag) + 1] = value
    else:
        args += [flag, value]
    status, stdout, stderr = run_cli(*args)
    assert "Traceback" not in stderr and status in (0, 2), (status, stderr)
    if status == 2:
        assert stderr.count("\n") == 1 and stderr.startswith("axiscal: error: "), stderr
        return
    written = out.read_text() if out.exists() else stdout
    for line in written.splitlines():
        if line.startswith(("G0", "G1", "step ")):
            words = [w for w in line.split() if w[:1] in "XF" and w[1:2] not in ("", "M")]
            assert all(WORD.fullmatch(w) for w in words), line
