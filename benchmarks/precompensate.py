"""Whole-process time and peak memory of ``axiscal precompensate`` on 10^6 and 10^7-line part programs.

Run from the repository root::

    .venv/bin/python benchmarks/precompensate.py [--lines 1000000 10000000] [--runs 3] [--baseline REV]
        [--numbered] [--dialect fanuc]
    .venv/bin/python benchmarks/precompensate.py --stages [--lines 100000] [--runs 5]

Makes seeded programs like a CAM system's finishing pass (short feed moves of 0.2 to 2 mm wandering
over the XFYZ example's travel, an arc every 200 blocks, a comment every 500, a G0 retract and a new
feed every 1000; ``--numbered``: a block number on every block; ``--dialect fanuc``: FANUC's
words, every number with its point) and times ``axiscal precompensate`` as a whole process
(start-up, reading, the model's inverse, the path checks, writing) ``--runs`` times for each size,
printing the median time, the median CPU time (user + system of all its threads, ``wait4``'s
``ru_utime + ru_stime``: what a shared machine's load disturbs least) and the peak resident memory
(``ru_maxrss``) with the load average seen during the runs. Up to ``--baseline-up-to`` lines
(2 x 10^6), the source of ``--baseline`` (default: the last revision that held the whole program
in memory) is run too,
unpacked from git into a temporary folder, alternating with this tree, and the two outputs are
compared: the same program must come out, to the byte. ``--baseline none`` times this tree alone.
``--stages`` times, in one process, the reading of the program in bulk and block by block, the
model's inverse of its points compiled and in NumPy, and then (CPU and wall time) the program read
in pieces alone, rewritten in pieces one piece after the other and with the next piece read ahead,
and the model's inverse and error alone at as many points as the rewriting gives them.
"""

from __future__ import annotations

import argparse
import filecmp
import math
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from io import BytesIO
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
MACHINE = ROOT / "examples" / "xfyz_machine" / "machine.toml"
#: the last revision that held the whole program in memory (read in bulk, rewritten at once)
BASELINE = "fb977f6"


def program_lines(lines: int, seed: int = 1, *, numbered: bool = False, dialect: str = "linuxcnc"):
    """The lines of a finishing pass of about ``lines`` blocks inside X 100..700, Y 100..400, Z 100..300 mm.

    Short feed moves, an arc every 200 blocks, a comment every 500, a G0 retract and a new feed
    every 1000; ``numbered``: a block number on every block (N10, N20, ...); FANUC: G00/G01, every
    number with its decimal point, the tape's % and program number.
    """
    rng = np.random.default_rng(seed)
    fanuc = dialect == "fanuc"
    g0, g1, g2 = ("G00", "G01", "G02") if fanuc else ("G0", "G1", "G2")
    head = ["%", "O0001", "(finishing pass)", "G21", "G90 G94 G17"] if fanuc else ["%", "(finishing pass)", "G21 G90 G94 G17"]
    count = 0

    def block(text: str) -> str:
        nonlocal count
        count += 1
        return f"N{10 * count} {text}" if numbered and not text.startswith(("%", "(", "O")) else text

    for line in head + [f"{g0} X400. Y250. Z200.", f"{g1} F1500."]:
        yield block(line)
    x, y, z = 400.0, 250.0, 200.0
    heading = 0.0
    written = len(head) + 2
    while written < lines - 2:
        heading += rng.normal(0.0, 0.4)
        step = rng.uniform(0.2, 2.0)
        nx, ny = x + step * math.cos(heading), y + step * math.sin(heading)
        if not (100 < nx < 700 and 100 < ny < 400):
            heading += math.pi
            continue
        z = min(300.0, max(100.0, z + rng.normal(0.0, 0.05)))
        if written % 200 == 0:
            # a half circle of radius `step` / 2 to the next point, by its radius
            yield block(f"{g2} X{nx:.4f} Y{ny:.4f} R{step / 2 + 1e-4:.4f}")
            yield block(g1)
            written += 1
        elif written % 1000 == 500:
            yield block(f"{g0} Z{z + 5:.4f}")
            yield block(f"{g1} X{nx:.4f} Y{ny:.4f} Z{z:.4f} F{rng.choice([900, 1200, 1500])}.")
            written += 1
        elif written % 500 == 0:
            yield block(f"X{nx:.4f} Y{ny:.4f} Z{z:.4f} (row {written})")
        else:
            yield block(f"X{nx:.4f} Y{ny:.4f} Z{z:.4f}")
        written += 1
        x, y = nx, ny
    yield block("M30" if fanuc else "M2")
    yield "%"


def part_program(lines: int, seed: int = 1, *, numbered: bool = False, dialect: str = "linuxcnc") -> str:
    """:func:`program_lines` as one text."""
    return "\n".join(program_lines(lines, seed, numbered=numbered, dialect=dialect)) + "\n"


def write_part_program(path: Path, lines: int, *, numbered: bool = False, dialect: str = "linuxcnc") -> None:
    """:func:`part_program` written to ``path`` a block of lines at a time."""
    with open(path, "w") as out:
        batch = []
        for line in program_lines(lines, numbered=numbered, dialect=dialect):
            batch.append(line)
            if len(batch) == 100_000:
                out.write("\n".join(batch) + "\n")
                batch = []
        out.write("\n".join(batch) + "\n")


def unpack(revision: str, folder: Path) -> Path:
    """The ``src`` folder of ``revision`` written under ``folder``."""
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", "--format=tar", revision, "src"],
                             check=True, capture_output=True).stdout
    with tarfile.open(fileobj=BytesIO(archive)) as tar:
        tar.extractall(folder, filter="data")
    return folder / "src"


def run(source: Path, program: Path, output: Path, dialect: str = "linuxcnc") -> tuple[float, float, float]:
    """Seconds, peak resident memory (MB) and CPU seconds (user + system, every thread) of one whole
    ``axiscal precompensate`` process run on ``source``."""
    env = dict(os.environ, PYTHONPATH=str(source))
    start = time.perf_counter()
    child = subprocess.Popen([sys.executable, "-m", "axiscal.cli.main", "precompensate", str(program), "--machine",
                              str(MACHINE), "--dialect", dialect, "-o", str(output)], env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(child.pid, 0)
    seconds = time.perf_counter() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    if child.returncode:
        raise SystemExit(f"precompensate failed: {child.stderr.read().decode()}")
    child.stderr.close()
    return seconds, usage.ru_maxrss / 1024.0, usage.ru_utime + usage.ru_stime


def stages(lines: int, runs: int) -> None:
    """In-process: the reading of the program, and the model's inverse of as many points compiled and in NumPy."""
    from axiscal.io.gcode import read_program
    from axiscal.model import kinematics
    from axiscal.model.machine import load_machine

    text = part_program(lines)
    machine = load_machine(MACHINE)
    from axiscal.io.gcode import reader

    read_program(text, dialect="linuxcnc")  # the compiled scan loaded from numba's cache (or compiled)
    for label, bulk in (("in bulk", True), ("block by block", False)):
        reader._BULK = bulk
        times = []
        for _ in range(runs):
            start = time.perf_counter()
            program = read_program(text, dialect="linuxcnc")
            program.columns if bulk else program.blocks  # what each way hands on to the rewriting
            times.append(time.perf_counter() - start)
        print(f"  {lines:>9,} lines, reading the program {label:<15}: {statistics.median(times):6.2f} s")
    reader._BULK = True
    moves = [m for m in program.motions if m.kind != "dwell"]
    points = np.array([[m.end_m["X"], m.end_m["Y"], m.end_m["Z"]] for m in moves])
    target = machine.nominal_point({k: points[:, j] for j, k in enumerate("XYZ")})
    kinematics._COMPILED_FROM = 0
    machine.command_for(target[:1000])  # the compiled functions loaded from numba's cache (or compiled)
    for label, start_at in (("compiled", 0), ("NumPy", 1 << 62)):
        kinematics._COMPILED_FROM = start_at
        times = []
        for _ in range(runs):
            start = time.perf_counter()
            machine.command_for(target)
            times.append(time.perf_counter() - start)
        print(f"  {lines:>9,} lines, the inverse of {len(target):,} points, {label:<8}: {statistics.median(times):6.2f} s")
    kinematics._COMPILED_FROM = 65536
    pieces(text, machine, runs)


def pieces(text: str, machine, runs: int) -> None:
    """CPU and wall time of the program read in pieces alone, rewritten in pieces one piece after the
    other and with the next piece read ahead on a thread, and the model's inverse and forward error
    alone at as many points as the rewriting gives them (counted in a first run)."""
    import io

    from axiscal.io.gcode.stream import read_pieces, text_pieces
    from axiscal.precompensation import path, streaming

    data = text.encode()

    def timed(work) -> tuple[float, float]:
        cpu, wall = time.process_time(), time.perf_counter()
        work()
        return time.process_time() - cpu, time.perf_counter() - wall

    def read() -> None:
        for _ in read_pieces(text_pieces(BytesIO(data), piece_bytes=streaming.PIECE_BYTES), dialect="linuxcnc"):
            pass

    def rewrite(threaded: bool) -> None:
        streaming.rewrite_pieces(text_pieces(BytesIO(data), piece_bytes=streaming.PIECE_BYTES), io.BytesIO().write,
                                 machine, dialect="linuxcnc", threaded=threaded)

    counted = {"inverse": 0, "forward": 0}
    solve, deviation = path.solve_commands, path._deviation

    def counting_solve(model, programmed):
        counted["inverse"] += len(next(iter(programmed.values())))
        return solve(model, programmed)

    def counting_deviation(model, command, *rest):
        counted["forward"] += len(command)
        return deviation(model, command, *rest)

    path.solve_commands, path._deviation = counting_solve, counting_deviation
    try:
        rewrite(False)
    finally:
        path.solve_commands, path._deviation = solve, deviation
    rng = np.random.default_rng(1)

    def points(n: int) -> dict:
        return {"X": rng.uniform(0.1, 0.7, n), "Y": rng.uniform(0.1, 0.4, n), "Z": rng.uniform(0.1, 0.3, n)}

    target = machine.actual_point(points(counted["inverse"]))
    samples = points(counted["forward"])
    work = {
        "read in pieces, alone": read,
        "rewritten, one piece after the other": lambda: rewrite(False),
        "rewritten, the next piece read ahead": lambda: rewrite(True),
        f"the inverse alone, {counted['inverse']:,} points": lambda: machine.command_for(target, tolerance_m=1e-11),
        f"the error alone, {counted['forward']:,} samples": lambda: machine.actual_point(samples) - machine.nominal_point(samples),
    }
    for label, job in work.items():
        times = [timed(job) for _ in range(runs)]
        print(f"  {label:<46}: CPU {statistics.median(t[0] for t in times):6.2f} s, wall"
              f" {statistics.median(t[1] for t in times):6.2f} s; load average {os.getloadavg()[0]:.1f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, nargs="+", default=[1_000_000, 10_000_000])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--baseline", default=BASELINE, help="git revision timed alongside ('none': this tree alone)")
    parser.add_argument("--baseline-up-to", type=int, default=2_000_000,
                        help="largest program the baseline is run on (it holds the whole program in memory)")
    parser.add_argument("--numbered", action="store_true", help="a block number on every block")
    parser.add_argument("--dialect", default="linuxcnc", choices=["linuxcnc", "fanuc"])
    parser.add_argument("--stages", action="store_true", help="time the reading and the inverse in this process instead")
    args = parser.parse_args()
    if args.stages:
        print(f"stages of axiscal precompensate in this process, median of {args.runs}; load average {os.getloadavg()[0]:.1f}")
        for lines in args.lines:
            stages(lines, args.runs)
        return
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        paths = {"this tree": ROOT / "src"}
        if args.baseline != "none":
            paths[f"baseline {args.baseline}"] = unpack(args.baseline, folder / "baseline")
        print(f"axiscal precompensate, whole process (start-up, read, solve, check, write), median of {args.runs};"
              f" {args.dialect}{', numbered blocks' if args.numbered else ''}; {os.cpu_count()} cores")
        for lines in args.lines:
            program = folder / f"part_{lines}.ngc"
            write_part_program(program, lines, numbered=args.numbered, dialect=args.dialect)
            size = program.stat().st_size / 1e6
            here = {label: source for label, source in paths.items() if label == "this tree" or lines <= args.baseline_up_to}
            for label, source in here.items():  # a first run of each: numba's cache written, files read once
                run(source, program, folder / f"{label.split()[0]}.ngc", args.dialect)
            results: dict[str, list[tuple[float, float, float]]] = {label: [] for label in here}
            load = []
            for _ in range(args.runs):
                for label, source in here.items():
                    load.append(os.getloadavg()[0])
                    results[label].append(run(source, program, folder / f"{label.split()[0]}.ngc", args.dialect))
            same = len(here) == 1 or filecmp.cmp(folder / "this.ngc", folder / "baseline.ngc", shallow=False)
            for label, values in results.items():
                seconds = statistics.median(v[0] for v in values)
                cpu = statistics.median(v[2] for v in values)
                print(f"  {lines:>10,} lines ({size:.0f} MB), {label:<18}: {seconds:6.2f} s, {lines / seconds:9,.0f} lines/s,"
                      f" CPU {cpu:6.2f} s ({lines / cpu:,.0f} lines per CPU s), peak {max(v[1] for v in values):6.0f} MB"
                      f" (runs {', '.join(f'{v[0]:.2f}' for v in values)})")
            print(f"  {lines:>10,} lines: load average {min(load):.1f} to {max(load):.1f} during the runs"
                  + ("" if len(here) == 1 else f"; outputs {'identical' if same else 'DIFFER'}"))
            program.unlink()


if __name__ == "__main__":
    main()
