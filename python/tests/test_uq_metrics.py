"""The V&V 20 budget and the area validation metric of `impact._vv20` (issue 27).

References: ASME V&V 10.1-2012, validation approach 1 (tapered cantilever, tip deflection):
model N(-14.2, 0.71/3) mm against experiment N(-15.0, 0.75/3) mm, area metric 0.800 mm, 5.3 %
of the experimental mean (ASME V&V 10.1-2012, section 4, the worked example); two normals of equal mean, whose
area is |s2 - s1| sqrt(2 / pi) (the 1-Wasserstein distance) while the signed integral of
F_a - F_b is 0: an implementation that forgets the absolute value fails there. ASME V&V 20-2009
for E = S - D and u_val."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from impact._vv20 import area_metric, area_to_uniform, budget, empirical_cdf, printed_digit_uncertainty


def test_area_metric_reproduces_the_vv10_1_example():
    model = stats.norm(-14.2, 0.71 / 3).cdf
    experiment = stats.norm(-15.0, 0.75 / 3).cdf
    area = area_metric(model, experiment, -20.0, -10.0)
    assert area == pytest.approx(0.800, abs=5e-4)
    assert 100 * area / 15.0 == pytest.approx(5.3, abs=0.05)


def test_area_metric_is_the_absolute_not_the_signed_difference():
    a, b = stats.norm(0.0, 1.0).cdf, stats.norm(0.0, 2.0).cdf
    assert area_metric(a, b, -20, 20) == pytest.approx(math.sqrt(2 / math.pi), rel=1e-4)


def test_area_of_samples_against_a_printed_digit():
    # all samples at the centre: the area is the mean distance to a uniform of half-width a, a/2
    assert area_to_uniform([5.0] * 10, 5.0, 0.05) == pytest.approx(0.025, rel=1e-3)
    # samples far away: the area is the distance
    assert area_to_uniform([7.0] * 4, 5.0, 0.05) == pytest.approx(2.0, rel=1e-4)
    f = empirical_cdf([1.0, 2.0, 3.0, 4.0])
    assert list(f(np.array([0.5, 1.0, 2.5, 4.0]))) == [0.0, 0.25, 0.5, 1.0]


def test_budget_row():
    b = budget(s=222.1, d=221.2, u_num=0.18, u_input=1.81, u_d=0.0289)
    assert b["E"] == pytest.approx(0.9)
    assert b["u_val"] == pytest.approx(math.sqrt(0.18**2 + 1.81**2 + 0.0289**2))
    assert b["within"] and b["error_interval"][0] < 0 < b["error_interval"][1]
    assert not budget(s=379.1, d=1106.0, u_num=60.0, u_input=15.0, u_d=0.3)["within"]
    with pytest.raises(ValueError, match="u_num"):
        budget(1.0, 1.0, -1.0, 0.0, 0.0)


def test_printed_digits_give_u_d_never_zero():
    assert printed_digit_uncertainty("221.2") == pytest.approx(0.05 / math.sqrt(3))
    assert printed_digit_uncertainty("-4.802", 1e-3) == pytest.approx(0.5e-6 / math.sqrt(3))
    assert printed_digit_uncertainty("1106", 1e3) == pytest.approx(500 / math.sqrt(3))
