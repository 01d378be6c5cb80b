"""Flatness from lines: Moody's published Union Jack reproduced, a surface of known shape recovered
by both evaluations, the minimum zone against a plain search over the planes it can be, refusals."""

from __future__ import annotations

from itertools import combinations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as hs

from axiscal.errors import AxiscalError
from axiscal.flatness import FlatnessLine, flatness_zone, line_from_angles, moody_union_jack, surface_from_lines
from axiscal.units import ARCSEC, INCH

# J. C. Moody, "How to calibrate surface plates in the plant", The Tool Engineer, October 1955: the
# readings (arcsec, 4-inch foot, 64 x 40 in plate) as corrected by B. Allen (2018), and his
# completed worksheets' heights (column 8, in 1e-5 inch, above the lowest point), line by line
MOODY = {
    "NW_SE": ("NW", "SE", [6.5, 6.0, 5.0, 5.2, 5.5, 5.6, 5.5, 5.0, 5.5, 4.8, 5.0, 5.2, 5.3, 4.9, 4.6, 4.2, 5.3, 4.9, 4.5, 3.5],
              [6.205611, 8.920568, 10.665896, 10.471972, 10.665896, 11.441598, 12.411225, 13.186928, 12.993002,
               13.768703, 13.186928, 12.993004, 13.186928, 13.574778, 13.186931, 12.217303, 10.471972, 10.859820,
               10.471969, 9.308419, 6.205611]),
    "NE_SW": ("NE", "SW", [6.6, 5.4, 5.4, 5.2, 5.5, 5.7, 5.0, 5.0, 5.4, 4.5, 4.4, 4.5, 4.5, 4.8, 4.2, 4.2, 4.2, 4.8, 4.3, 3.2],
              [2.908881, 6.321968, 7.407951, 8.493934, 9.192065, 10.471972, 12.139730, 12.450010, 12.760291,
               13.846274, 13.186928, 12.333656, 11.674312, 11.014964, 10.937392, 9.696272, 8.455150, 7.214028,
               7.136460, 6.089264, 2.908881]),
    "NE_NW": ("NE", "NW", [20.5, 19.7, 20.5, 20.3, 20.2, 19.9, 19.0, 19.5, 18.8, 18.6, 18.7, 18.6, 18.4, 18.5, 19.0, 17.9],
              [2.908881, 5.526869, 6.593460, 9.211453, 11.441594, 13.477812, 14.932251, 14.641363, 15.320102,
               14.641361, 13.574773, 12.702110, 11.635522, 10.181081, 8.920567, 8.629680, 6.205611]),
    "NE_SE": ("NE", "SE", [3.5, 2.1, 2.5, 2.8, 3.4, 3.2, 3.5, 4.0, 4.2, 3.5],
              [2.908881, 3.684582, 1.745328, 0.581776, 0.000000, 0.581776, 0.775701, 1.551402, 3.296731, 5.429910, 6.205611]),
    "SE_SW": ("SE", "SW", [16.4, 15, 15.6, 15.5, 15.1, 15.3, 15.1, 14.6, 14, 13.5, 13.5, 13.3, 13.3, 13.4, 14, 13.9],
              [6.205611, 9.744754, 10.568937, 12.556673, 14.350483, 15.368592, 16.774553, 17.792662, 17.841145,
               16.726072, 14.641376, 12.556676, 10.084127, 7.611578, 5.332953, 4.217880, 2.908881]),
    "NW_SW": ("NW", "SW", [6, 4.6, 4.5, 4.7, 5.0, 4.5, 5.9, 6, 6, 4.9],
              [6.205611, 7.407949, 5.895331, 4.188787, 2.870095, 2.133178, 0.426635, 1.435048, 2.637385, 3.839723, 2.908881]),
    "E_W": ("E", "W", [11.7, 12.4, 12.1, 12.5, 12.0, 11.5, 11.5, 11.3, 11.3, 10.3, 10.8, 10.3, 10, 10.7, 10.4, 10.4],
            [1.939253, 3.005844, 5.429910, 7.272202, 9.890195, 11.538562, 12.217300, 12.896040, 13.186928,
             13.477815, 11.829450, 11.150712, 9.502346, 7.272203, 6.399539, 4.945097, 3.490656]),
    "N_S": ("N", "S", [6.6, 6.4, 6.3, 6.5, 6.6, 6.9, 7.5, 7.4, 7.1, 7],
            [15.320102, 15.126178, 14.544402, 13.768703, 13.380852, 13.186928, 13.574780, 15.126184, 16.483664,
             17.259365, 17.841145]),
}
MOODY_PLACES = {"NW": (0, 40), "NE": (64, 40), "SE": (64, 0), "SW": (0, 0), "N": (32, 40), "S": (32, 0), "E": (64, 20), "W": (0, 20)}


def moody_lines():
    return [line_from_angles(name, np.array(MOODY_PLACES[a]) * INCH, np.array(MOODY_PLACES[b]) * INCH,
                             np.array(readings) * ARCSEC, foot_m=4 * INCH)
            for name, (a, b, readings, _) in MOODY.items()]


def test_moodys_published_union_jack_is_reproduced():
    surface = moody_union_jack(moody_lines())
    heights = np.concatenate(surface.line_heights_m)
    lowest = heights.min()
    for line, h in zip(surface.lines, surface.line_heights_m):
        expected = MOODY[line.name][3]
        # Allen's worksheets are single-precision floats with pi = 3.141592
        np.testing.assert_allclose((h - lowest) / (1e-5 * INCH), expected, atol=2e-4, err_msg=line.name)
    assert (heights.max() - lowest) / (1e-5 * INCH) == pytest.approx(17.841145, abs=2e-4)
    assert surface.zone.minimum_zone_m <= surface.zone.least_squares_m <= heights.max() - lowest
    assert len(surface.closures) == 2


def union_jack(shape, width=1.2, depth=0.8, steps=(12, 8, 14)):
    """The 8 lines of a Union Jack over a surface z = shape(x, y), as a level reads them (exact)."""
    p = {"SW": (0, 0), "SE": (width, 0), "NE": (width, depth), "NW": (0, depth), "S": (width / 2, 0),
         "N": (width / 2, depth), "W": (0, depth / 2), "E": (width, depth / 2)}
    plan = [("SW", "NE", steps[2]), ("NW", "SE", steps[2]), ("SW", "SE", steps[0]), ("NW", "NE", steps[0]),
            ("SW", "NW", steps[1]), ("SE", "NE", steps[1]), ("W", "E", steps[0]), ("S", "N", steps[1])]
    lines = []
    for a, b, n in plan:
        start, end = np.array(p[a], float), np.array(p[b], float)
        t = np.linspace(0, 1, n + 1)
        xy = start + t[:, None] * (end - start)
        foot = np.hypot(*(end - start)) / n
        lines.append(line_from_angles(f"{a}-{b}", start, end, np.diff(shape(xy[:, 0], xy[:, 1])) / foot, foot_m=foot))
    return lines


def about_plane(x, y, z):
    design = np.column_stack([x, y, np.ones_like(x)])
    coef, *_ = np.linalg.lstsq(design, z, rcond=None)
    return z - design @ coef


@pytest.mark.parametrize("evaluate", [surface_from_lines, moody_union_jack])
def test_a_surface_with_a_known_twist_is_recovered(evaluate):
    k = 2e-6  # z = k u v over the plate: a twist of 2k corner to corner; its flatness is 2k either way
    def twist(x, y):
        return k * (x / 0.6 - 1) * (y / 0.4 - 1)
    surface = evaluate(union_jack(twist))
    truth = about_plane(surface.x_m, surface.y_m, twist(surface.x_m, surface.y_m))
    np.testing.assert_allclose(surface.z_m, truth, atol=1e-15)
    assert surface.zone.least_squares_m == pytest.approx(2 * k, rel=1e-9)
    assert surface.zone.minimum_zone_m == pytest.approx(2 * k, rel=1e-9)
    assert surface.closure_max_m < 1e-15


def test_a_bowl_and_a_tilt_are_recovered_and_the_tilt_does_not_count():
    def bowl(x, y):
        return 3e-6 * ((x / 0.6 - 1) ** 2 + (y / 0.4 - 1) ** 2) + 5e-5 * x - 2e-5 * y
    surface = surface_from_lines(union_jack(bowl))
    truth = about_plane(surface.x_m, surface.y_m, bowl(surface.x_m, surface.y_m))
    np.testing.assert_allclose(surface.z_m, truth, atol=1e-15)
    assert surface.zone.minimum_zone_m == pytest.approx(6e-6, rel=1e-9)  # centre 0, corners 6 um above


def test_closure_errors_show_where_a_line_disagrees():
    lines = union_jack(lambda x, y: 0 * x)
    bad = lines[6]  # the W-E centre line reads 1 um high at its middle station only
    height = bad.height_m.copy()
    height[6] += 1e-6
    lines[6] = FlatnessLine(bad.name, bad.start_m, bad.end_m, bad.distance_m, height)
    least = surface_from_lines(lines)
    worst = max(least.closures, key=lambda c: c.value_m)
    assert (worst.x_m, worst.y_m) == pytest.approx((0.6, 0.4)) and "W-E" in worst.lines
    assert 0.3e-6 < worst.value_m < 1e-6 and least.closure_max_m == worst.value_m
    moody = moody_union_jack(lines)
    assert [c.value_m for c in moody.closures] == pytest.approx([1e-6, 0.0], abs=1e-15)


def test_rows_and_columns_alone_cannot_see_a_twist():
    lines = []
    for y in (0.0, 0.4, 0.8):
        lines.append(FlatnessLine(f"row {y}", [0, y], [1.2, y], np.linspace(0, 1.2, 5), np.zeros(5)))
    for x in (0.0, 0.6, 1.2):
        lines.append(FlatnessLine(f"col {x}", [x, 0], [x, 0.8], np.linspace(0, 0.8, 3), np.zeros(3)))
    with pytest.raises(AxiscalError, match="twist"):
        surface_from_lines(lines)
    lines.append(FlatnessLine("diagonal", [0, 0], [1.2, 0.8], np.linspace(0, np.hypot(1.2, 0.8), 3), np.zeros(3)))
    assert surface_from_lines(lines).zone.minimum_zone_m == 0.0


def test_a_line_that_crosses_no_other_is_refused_by_name():
    a = FlatnessLine("a", [0, 0], [1, 0], [0, 1], [0, 0])
    b = FlatnessLine("b", [0, 1], [1, 2], [0, 1], [0, 0])
    with pytest.raises(AxiscalError, match="line 'a' crosses the other lines at 0"):
        surface_from_lines([a, b])


def test_moody_needs_a_union_jack():
    lines = moody_lines()
    with pytest.raises(AxiscalError, match="8 lines"):
        moody_union_jack(lines[:7])
    moved = lines[7]
    lines[7] = FlatnessLine(moved.name, moved.start_m + [0.01, 0], moved.end_m + [0.01, 0], moved.distance_m, moved.height_m)
    with pytest.raises(AxiscalError, match="N_S"):
        moody_union_jack(lines)


def plain_minimum_zone(x, y, z):
    """Reference: the zone's planes touch 3 points and 1, or 2 and 2; try every such plane's slope."""
    points = np.column_stack([x, y, z])
    slopes = []
    for i, j, k in combinations(range(len(z)), 3):
        normal = np.cross(points[j] - points[i], points[k] - points[i])
        if abs(normal[2]) > 1e-12:
            slopes.append((-normal[0] / normal[2], -normal[1] / normal[2]))
    for (i, j), (k, l) in combinations(list(combinations(range(len(z)), 2)), 2):
        normal = np.cross(points[j] - points[i], points[l] - points[k])
        if abs(normal[2]) > 1e-12:
            slopes.append((-normal[0] / normal[2], -normal[1] / normal[2]))
    return min(np.ptp(z - a * x - b * y) for a, b in slopes)


@pytest.mark.parametrize("seed", range(8))
def test_the_minimum_zone_agrees_with_a_plain_search(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(4, 9))
    x, y = rng.uniform(0, 1.0, n), rng.uniform(0, 0.7, n)
    z = rng.normal(0, 2e-6, n) + 1e-5 * x
    zone = flatness_zone(x, y, z)
    assert zone.minimum_zone_m == pytest.approx(plain_minimum_zone(x, y, z), rel=1e-7, abs=1e-14)
    a, b, c = zone.minimum_zone_plane
    residual = z - (a * x + b * y + c)
    assert residual.min() >= -1e-13 and residual.max() <= zone.minimum_zone_m + 1e-13


def test_points_that_do_not_span_a_plane_are_refused():
    with pytest.raises(AxiscalError, match="one line"):
        flatness_zone([0, 1, 2], [0, 1, 2], [0, 0, 0])
    with pytest.raises(AxiscalError, match="at least 3"):
        flatness_zone([0, 1], [0, 1], [0, 0])


@settings(max_examples=60, deadline=None)
@given(hs.lists(hs.tuples(hs.floats(-1e3, 1e3), hs.floats(-1e3, 1e3), hs.floats(-1e-3, 1e-3)), min_size=3, max_size=10))
def test_the_minimum_zone_is_never_wider_than_the_least_squares_zone(points):
    x, y, z = (np.array(v) for v in zip(*points))
    try:
        zone = flatness_zone(x, y, z)
    except AxiscalError:
        return
    assert 0.0 <= zone.minimum_zone_m <= zone.least_squares_m


def level_lines(shape, segments, *, gravity):
    """Lines read by a level over z = shape(x, y): (name, start, end, steps) each, rises exact."""
    lines = []
    for name, start, end, steps in segments:
        start, end = np.array(start, float), np.array(end, float)
        xy = start + np.linspace(0, 1, steps + 1)[:, None] * (end - start)
        foot = np.hypot(*(end - start)) / steps
        lines.append(line_from_angles(name, start, end, np.diff(shape(xy[:, 0], xy[:, 1])) / foot, foot_m=foot,
                                      gravity=gravity))
    return lines


def test_levels_against_gravity_tie_rows_and_columns_without_a_diagonal():
    def plate(x, y):  # a twist and a bow, the whole plate tilted against gravity by 30 urad and 10 urad
        u, v = x / 0.6 - 1, y / 0.4 - 1
        return 2e-6 * u * v + 1e-6 * (u * u + v * v) + 30e-6 * x - 10e-6 * y
    grid = [(f"y{y}", (0, y), (1.2, y), 6) for y in (0.0, 0.4, 0.8)] + [(f"x{x}", (x, 0), (x, 0.8), 4) for x in (0.0, 0.6, 1.2)]
    with pytest.raises(AxiscalError, match="twist"):
        surface_from_lines(level_lines(plate, grid, gravity=False))
    surface = surface_from_lines(level_lines(plate, grid, gravity=True))
    truth = about_plane(surface.x_m, surface.y_m, plate(surface.x_m, surface.y_m))
    np.testing.assert_allclose(surface.z_m, truth, atol=1e-15)
    assert surface.closure_max_m < 1e-15


def test_a_union_jack_against_gravity_gives_the_same_surface():
    def plate(x, y):
        return 1.5e-6 * np.sin(3 * x) * np.cos(4 * y) + 20e-6 * x
    free = surface_from_lines(union_jack(plate))
    lines = [FlatnessLine(line.name, line.start_m, line.end_m, line.distance_m, line.height_m, True)
             for line in union_jack(plate)]
    tied = surface_from_lines(lines)
    np.testing.assert_allclose(tied.z_m, free.z_m, atol=1e-15)
    np.testing.assert_allclose(tied.z_m, about_plane(tied.x_m, tied.y_m, plate(tied.x_m, tied.y_m)), atol=1e-15)


def test_a_line_against_gravity_is_placed_by_one_crossing():
    base = [FlatnessLine("a", [0, 0], [1, 0], [0, 0.5, 1], [0, 0, 0], True),
            FlatnessLine("b", [0, 0], [0, 1], [0, 0.5, 1], [0, 1e-6, 2e-6], True),
            FlatnessLine("c", [0.5, 0], [0.5, 1], [0, 0.5, 1], [0, 1e-6, 2e-6], True)]
    spur = FlatnessLine("d", [0, 1], [-1, 1], [0, 1], [0, 0], True)
    surface = surface_from_lines([*base, spur])
    assert surface.zone.minimum_zone_m == pytest.approx(0.0, abs=1e-15)  # one plane rising along y
    with pytest.raises(AxiscalError, match="line 'd' crosses the other lines at 1"):
        surface_from_lines([*base, FlatnessLine("d", [0, 1], [-1, 1], [0, 1], [0, 0])])


def bowl_3600(x, y):
    """A bowl 3.600 um deep from the corners to the centre of a 1.2 x 0.8 m plate."""
    return 1.8e-6 * ((x / 0.6 - 1) ** 2 + (y / 0.4 - 1) ** 2)


@pytest.mark.parametrize("evaluate", [surface_from_lines, moody_union_jack])
def test_a_union_jack_without_stations_where_its_lines_cross_is_refused_by_both_evaluations(evaluate):
    """11 steps along x leave the W-E centre line and the S and N edges without a middle station: Moody's
    method interpolated there (the 3.600 um bowl read 3.570 um, with 0.030 um closures that are not in the
    readings) and least squares refused it speaking of rows and columns. Both now name the lines and the place."""
    assert moody_union_jack(union_jack(bowl_3600)).zone.minimum_zone_m == pytest.approx(3.6e-6, rel=1e-9)
    with pytest.raises(AxiscalError) as caught:
        evaluate(union_jack(bowl_3600, steps=(11, 8, 14)))
    assert caught.value.message.startswith("lines 'SW-NE' and 'W-E' cross at x = 600 mm, y = 400 mm, where 'W-E' has no"
                                           " station: lines are joined only at stations they share")


def test_a_centre_line_ending_between_an_edge_s_stations_is_refused():
    """The S-N centre line ends on the S edge's middle; 11 steps along x put no station of the edge there."""
    lines = union_jack(bowl_3600, steps=(12, 8, 14))
    edge = union_jack(bowl_3600, steps=(11, 8, 14))[2]  # SW-SE with 11 steps
    lines[2] = edge
    with pytest.raises(AxiscalError, match=r"lines 'SW-SE' and 'S-N' cross at x = 600 mm, y = 0 mm, where 'SW-SE' has no"):
        moody_union_jack(lines)


def test_a_grid_line_whose_stations_miss_the_crossings_is_refused():
    """A row stepped half a pitch off the columns met them only at its ends, and was silently joined there alone."""
    def plate(x, y):
        return 2e-6 * (x / 0.6 - 1) * (y / 0.4 - 1)
    lines = []
    for y in (0.0, 0.4, 0.8):
        s = np.linspace(0, 1.2, 5) if y != 0.4 else np.r_[0.0, np.linspace(0.15, 1.05, 4), 1.2]
        lines.append(FlatnessLine(f"row {y:g}", [0, y], [1.2, y], s, plate(s, y)))
    for x in (0.0, 0.6, 1.2):
        s = np.linspace(0, 0.8, 3)
        lines.append(FlatnessLine(f"col {x:g}", [x, 0], [x, 0.8], s, plate(x, s)))
    d = np.linspace(0, np.hypot(1.2, 0.8), 3)
    lines.append(FlatnessLine("diagonal", [0, 0], [1.2, 0.8], d, plate(d / np.hypot(1.2, 0.8) * 1.2, d / np.hypot(1.2, 0.8) * 0.8)))
    with pytest.raises(AxiscalError, match=r"lines 'row 0.4' and 'col 0.6' cross at x = 600 mm, y = 400 mm, where 'row 0.4'"):
        surface_from_lines(lines)
