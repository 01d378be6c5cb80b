"""Draw docs/squareness_conventions.png: the ISO 230-1 sign and the included angle in each plane.

Run from the repository root: ``.venv/bin/python docs/squareness_figure.py``. Each panel shows the
reference (first) axis, the nominal second axis (dashed) and the second axis turned by a POSITIVE
ISO term (angle exaggerated to 12 degrees), with the third axis' direction marked (out of or into
the page) so that the right-hand rule can be read off.
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = Path(__file__).resolve().parent / "squareness_conventions.png"
TILT = math.radians(12.0)

# (title, first axis, second axis, third axis, whether the third axis points out of the page)
PANELS = [
    ("XY: EC0Y > 0", "X", "Y", "Z", True),
    ("XZ: EB0Z > 0", "X", "Z", "Y", False),
    ("YZ: EA0Z > 0", "Y", "Z", "X", True),
]


def panel(ax, title, first, second, third, out_of_page):
    # a positive rotation about an axis pointing out of the page is counter-clockwise on the page;
    # about an axis pointing into the page it is clockwise
    angle = TILT if out_of_page else -TILT
    ax.annotate("", xy=(1.0, 0.0), xytext=(0, 0), arrowprops=dict(arrowstyle="->", lw=2))
    ax.text(1.04, -0.04, f"+{first}", fontsize=12)
    ax.plot([0, 0], [0, 1.0], "--", color="0.6")
    end = (-math.sin(angle), math.cos(angle))
    ax.annotate("", xy=end, xytext=(0, 0), arrowprops=dict(arrowstyle="->", lw=2, color="tab:red"))
    ax.text(end[0] - 0.05, end[1] + 0.05, f"+{second}", fontsize=12, color="tab:red")
    included = 90.0 + math.degrees(angle)
    arc = [math.radians(t) for t in range(0, int(round(included)) + 1)]
    ax.plot([0.25 * math.cos(t) for t in arc], [0.25 * math.sin(t) for t in arc], color="tab:blue")
    ax.text(0.28, 0.28, f"{included:.0f} deg", color="tab:blue", fontsize=10)
    marker = "\u2299" if out_of_page else "\u2297"
    ax.text(-0.12, -0.12, f"{marker} +{third}", fontsize=12, ha="center", va="center")
    s = included - 90.0
    ax.set_title(f"{title}\nincluded angle - 90 = {s:+.0f} deg (exaggerated)", fontsize=10)
    ax.text(-0.25, -0.32, f"ISO term +, included-angle value {'+' if s > 0 else '-'}", fontsize=9)
    ax.set_xlim(-0.45, 1.25)
    ax.set_ylim(-0.4, 1.2)
    ax.set_aspect("equal")
    ax.axis("off")


def main() -> None:
    fig, axes = plt.subplots(1, 3, figsize=(10, 3.8), constrained_layout=True)
    for ax, spec in zip(axes, PANELS):
        panel(ax, *spec)
    fig.savefig(OUT, dpi=80)
    plt.close(fig)


if __name__ == "__main__":
    main()
