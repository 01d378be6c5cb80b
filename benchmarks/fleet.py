"""Speed of a fleet report: 200 generated campaigns, in one local process vs a 2-worker Dask LocalCluster.

Run: .venv/bin/python benchmarks/fleet.py [--machines 50] [--campaigns 4]

Generates machines x campaigns campaign folders (axiscal.fleet.generated_fleet: one ISO 230-2
positioning run of 11 targets x 5 bidirectional runs each), then writes every campaign's report and
the fleet page three ways: in this process with one thread (the reports one after another), in
this process with two threads (pyplot is not thread-safe, so the reports still take turns), and
on a LocalCluster of two single-threaded worker processes (its start included in the time). Prints the
wall time and campaigns per second of each.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from axiscal.fleet import fleet_report, generated_fleet


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--machines", type=int, default=50)
    parser.add_argument("--campaigns", type=int, default=4)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        generated_fleet(folder / "plant", machines=args.machines, campaigns=args.campaigns)
        total = args.machines * args.campaigns
        for label, options in (("one process (threads, 1 worker)", {"scheduler": "threads", "workers": 1}),
                               ("threads, 2 workers", {"scheduler": "threads", "workers": 2}),
                               ("LocalCluster, 2 worker processes", {"scheduler": "local", "workers": 2})):
            start = time.perf_counter()
            fleet = fleet_report(folder / "plant", folder / label.split()[0], **options)
            elapsed = time.perf_counter() - start
            assert fleet.failed == 0 and len(fleet.machines) == args.machines
            print(f"{label:34s} {total} campaigns in {elapsed:6.1f} s: {total / elapsed:5.2f} campaigns/s")


if __name__ == "__main__":
    main()
