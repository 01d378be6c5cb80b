"""One call from a trace to the figures, the JSON object, the text report and the polar plot."""

from __future__ import annotations

import math

import pytest

from axiscal.circular.evaluation import MM_PER_MIN
from axiscal.circular.report import (
    MS,
    ballbar_payload,
    evaluate_ballbar,
    evaluate_ballbar_file,
    iso_squareness,
    render_report,
)
from axiscal.circular.simulation import simulate_ballbar
from axiscal.errors import AxiscalError
from axiscal.units import ANGLE_UNITS, MM, UM

URAD = ANGLE_UNITS["urad"]
KEYS = ("G_ccw_um", "G_cw_um", "H_um", "F_max_um", "F_min_um", "centre_x_um", "centre_y_um", "squareness_urad",
        "scale_mismatch_ppm", "backlash_um", "reversal_spike_um", "cyclic_error_um", "servo_mismatch_ms")


@pytest.fixture(scope="module")
def result():
    trace = simulate_ballbar(squareness=12 * URAD, backlash={"X": 3 * UM}, servo_mismatch=1 * MS, step=math.radians(0.5))
    return evaluate_ballbar(trace, feed=1000 * MM_PER_MIN)


def test_payload_has_every_key_in_file_units(result):
    p = ballbar_payload(result)
    for key in KEYS:
        assert key in p
    assert p["squareness_urad"] == pytest.approx(12.0, rel=0.02)
    assert p["backlash_um"]["X"] == pytest.approx(3.0, rel=0.02)
    assert p["servo_mismatch_ms"] == pytest.approx(1.0, rel=0.02)
    assert p["feed_mm_min"] == pytest.approx(1000.0)
    assert set(p["reversal_spike_um"]["X"]) == {"ccw", "cw"}
    assert p["squareness_iso_term"] == "EC0Y" and p["squareness_iso_urad"] == p["squareness_urad"]


def test_single_direction_payload_has_nulls():
    p = ballbar_payload(evaluate_ballbar(simulate_ballbar(directions=("ccw",), step=math.radians(1.0))))
    assert p["G_cw_um"] is None and p["H_um"] is None and p["servo_mismatch_ms"] is None and p["warnings"]


def test_report_text(result):
    text = render_report(result)
    assert "G ccw  circular deviation" in text and "EC0Y" in text and "X backlash" in text
    assert not text.endswith("\n")


@pytest.mark.parametrize("plane, term, sign", [("XY", "EC0Y", 1), ("YX", "EC0Y", 1), ("XZ", "EB0Z", -1), ("ZX", "EB0Z", -1),
                                               ("YZ", "EA0Z", 1), ("ZY", "EA0Z", 1)])
def test_iso_terms_follow_docs_conventions(plane, term, sign):
    # docs/conventions.md: angle(+X,+Y) = 90 + EC0Y, angle(+X,+Z) = 90 - EB0Z, angle(+Y,+Z) = 90 + EA0Z
    assert iso_squareness(plane, 7 * URAD) == (term, sign * 7 * URAD)


def test_file_errors_name_the_file(tmp_path):
    with pytest.raises(AxiscalError) as caught:
        evaluate_ballbar_file(tmp_path / "none.csv", radius=100 * MM)
    assert caught.value.path.endswith("none.csv")


def test_polar_plot_is_written(result, tmp_path):
    from axiscal.circular.plot import plot_ballbar

    path = plot_ballbar(result, tmp_path / "polar.png")
    assert path.stat().st_size > 10_000 and path.read_bytes()[:4] == b"\x89PNG"
    with pytest.raises(AxiscalError, match="figure format"):
        plot_ballbar(result, tmp_path / "polar.txt")


def test_the_trace_payload_is_every_kth_point_of_the_plotted_deviation(result):
    from axiscal.circular.report import circle_deviations, trace_payload

    full = circle_deviations(result)
    thin = trace_payload(result, max_points=100)
    for d, (a, r) in full.items():
        step = math.ceil(a.size / 100)
        assert len(thin[d]["angle_deg"]) <= 100
        assert thin[d]["angle_deg"] == pytest.approx([math.degrees(v) for v in a[::step]], abs=1e-4)
        assert thin[d]["deviation_um"] == pytest.approx(list(r[::step] / UM), abs=1e-4)


def test_the_polar_scale_fits_an_overlay(result, tmp_path):
    from axiscal.circular.plot import plot_ballbar
    from axiscal.circular.report import trace_payload

    alone = plot_ballbar(result, tmp_path / "alone.svg").read_text()
    larger = {d: {"angle_deg": p["angle_deg"], "deviation_um": [3 * v for v in p["deviation_um"]]}
              for d, p in trace_payload(result).items()}
    text = plot_ballbar(result, tmp_path / "both.svg", overlay=larger).read_text()
    assert "before: ccw" in text and "before: cw" in text
    ring = lambda svg: svg.split("outer ring +", 1)[1].split(" ", 1)[0]  # noqa: E731
    assert float(ring(text)) > float(ring(alone))
