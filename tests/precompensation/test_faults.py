"""`axiscal precompensate` killed (SIGKILL) at random moments over an older output: the output is the
old program or the new one, whole, and a later run removes the temporaries killed runs left."""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import time

import numpy as np

from axiscal.precompensation import rewrite_program

#: kills at seeded random moments of a run (each a whole process: under 3 s)
TRIALS = 3


def _program(blocks: int) -> str:
    rng = np.random.default_rng(7)
    out, x, y, heading = ["%", "G21 G90 G94 G17", "G0 X400 Y250 Z200", "G1 F1500"], 400.0, 250.0, 0.0
    while len(out) < blocks:
        heading += rng.normal(0.0, 0.4)
        nx, ny = x + 2.0 * math.cos(heading), y + 2.0 * math.sin(heading)
        if 150 < nx < 650 and 150 < ny < 350:
            out.append(f"G1 X{nx:.4f} Y{ny:.4f}")
            x, y = nx, ny
        else:
            heading += math.pi
    return "\n".join(out + ["M2", "%"]) + "\n"


def _command(program, machine, output):
    return [sys.executable, "-m", "axiscal.cli.main", "precompensate", str(program), "--machine", str(machine),
            "--dialect", "linuxcnc", "-o", str(output)]


def test_a_killed_run_leaves_the_old_or_the_new_output_and_the_next_run_sweeps_its_temporaries(tmp_path, examples):
    machine = examples / "xfyz_machine" / "machine.toml"
    program, output = tmp_path / "part.ngc", tmp_path / "out.ngc"
    text = _program(5_000)
    program.write_text(text)
    new = rewrite_program(text, str(machine), dialect="linuxcnc", source=str(program)).text
    old = "(an older pre-compensated program)\nM2\n"
    output.write_text(old)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    rng = np.random.default_rng(28)
    outcomes = []
    # from the start-up to past the write (a whole run takes 1.5 to 3 s here)
    for delay in rng.uniform(0.5, 3.0, TRIALS):
        output.write_text(old)
        process = subprocess.Popen(_command(program, machine, output), env=env, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
        try:
            time.sleep(delay)
            process.send_signal(signal.SIGKILL)
            process.wait(timeout=30)
        finally:
            if process.poll() is None:
                process.kill()
        written = output.read_text()
        assert written in (old, new)
        outcomes.append(written == new)
    # a temporary of a killed run of this output, as SIGKILL in the write leaves it
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    stale = tmp_path / f".out.ngc.{child.pid}-k1ll3d00.ngc"
    stale.write_text(new[: len(new) // 2])
    subprocess.run(_command(program, machine, output), env=env, check=True, capture_output=True)
    assert output.read_text() == new
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.ngc", "part.ngc"], outcomes
