"""Write examples/campaign/: the campaign `axiscal demo` simulates (run from the repository root).

    python examples/make_campaign_example.py

One calibration campaign of paper 000's XZ module, every reading simulated by the virtual
instrument (axiscal.measurement.virtual.VirtualModule, seed 0): the sensor calibration, a 6-DOF
recording, ISO 230-2 laser runs of X and Z as raw readings with air and material sensors,
straightness of X by error separation, XZ squareness by pentaprism and the diagonal check unloaded
and with 2 kg, with campaign.toml in the format of docs/campaign.md. `axiscal report
examples/campaign` reports it.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from axiscal.measurement.campaign_sim import write_campaign

OUT = Path(__file__).resolve().parent / "campaign"


def main() -> None:
    if OUT.exists():
        shutil.rmtree(OUT)
    write_campaign(OUT, seed=0)


if __name__ == "__main__":
    main()
