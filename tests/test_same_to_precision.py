"""The comparison of regenerated files with shipped ones: the same to the precision printed, on any CPU."""

from __future__ import annotations

import pytest



def test_the_16th_digit_of_another_cpu_is_the_same_number(same_text_to_precision):
    same = same_text_to_precision
    # sensors_calibration.json as shipped and as regenerated on an AMD EPYC (another BLAS kernel)
    same('{"scale": 1.1848700499280698}\n', '{"scale": 1.1848700499280693}\n')


def test_a_printed_figure_whose_last_digit_flipped_is_the_same(same_text_to_precision):
    same = same_text_to_precision
    same("E_um,0.124\n", "E_um,0.123\n")
    same("x,1.5e-06\n", "x,1.6e-06\n")


@pytest.mark.parametrize(("a", "b"), [
    ('{"scale": 1.18487}\n', '{"scale": 1.18497}\n'),   # a real change at the printed precision
    ("runs,5\n", "runs,6\n"),                            # whole numbers are exact
    ("E_um,0.124\n", "E_mm,0.124\n"),                    # the words around the numbers are exact
    ("a\nb\n", "a\n"),                                   # every line
    ("x,1.0,2.0\n", "x,1.0\n"),                          # every number
])
def test_a_difference_in_meaning_fails(a, b, same_text_to_precision):
    with pytest.raises(AssertionError):
        same_text_to_precision(a, b)
