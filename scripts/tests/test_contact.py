import math

import numpy as np
import pytest

from helpers import scene
from indep_fe.contact import ContactLawExceeded, make_law

W = 0.2


def law_of(kind):
    sc = scene(**{"load.impactor.contact_law": kind})
    return make_law(sc.impactor, sc.material, W), sc


def test_paper_law_as_printed():
    law, sc = law_of({"paper": {"length_unit": 1.0e-3}})
    r, E, nus = 0.01, 207e9, 0.3
    c = (1 - nus ** 2) / (math.pi * E) + 1 / (math.pi * E)
    for P in [1e3, 1e6, 5e7]:
        printed = P * c * (1 - math.log(P * r * c / 1e-6))
        assert law.alpha(P) == pytest.approx(printed, rel=1e-12)
    assert law.p_star == pytest.approx(1e-6 / (r * c), rel=1e-12)
    assert law.dalpha(law.p_star) == pytest.approx(0.0, abs=1e-12 * law.b)


def test_johnson_law_matches_its_definition():
    law, sc = law_of({"johnson": {"datum_depth": 0.01}})
    r, d, E, nu = 0.01, 0.01, 207e9, 0.3
    chi = (1 - nu ** 2) / (math.pi * E)
    estar = 1 / (2 * (1 - nu ** 2) / E)
    for P in [1e4, 1e6, 1e7]:
        aH = math.sqrt(4 * P * r / (math.pi * estar))
        direct = (chi * P * (2 * math.log(4 * r / aH) - 1)
                  + chi * P * (2 * math.log(2 * d / aH) - nu / (1 - nu)))
        assert law.alpha(P) == pytest.approx(direct, rel=1e-12)


@pytest.mark.parametrize("kind", [{"paper": {"length_unit": 1.0}}, {"johnson": {"datum_depth": 0.01}}])
def test_contact_energy_is_the_potential(kind):
    law, _ = law_of(kind)
    # dE_c/dalpha = F along the law: check dE/dP = F alpha'(P) by central differences
    for P in [1e4, 1e6, 0.5 * law.p_star]:
        h = 1e-5 * P
        dE = (law.energy((P + h) * W) - law.energy((P - h) * W)) / (2 * h)
        assert dE == pytest.approx(P * W * law.dalpha(P), rel=1e-7)
    assert law.energy(0.0) == 0.0


@pytest.mark.parametrize("kind", [{"paper": {"length_unit": 1.0}}, {"johnson": {"datum_depth": 0.01}}])
def test_root_solve(kind):
    law, _ = law_of(kind)
    c = (1e-7) ** 2 / (6 * 18.0)
    for frac in [1e-9, 1e-4, 0.1, 0.7, 0.999999]:
        Ftrue = frac * W * law.p_star
        af = law.alpha(Ftrue / W) + c * Ftrue
        for guess in [None, Ftrue * 3, Ftrue * 1e-3]:
            F = law.solve(af, c, guess)
            # near P* the root is ill-conditioned (g' -> c): F is only as good as eps / (1 - frac)
            assert F == pytest.approx(Ftrue, rel=1e-12 if frac < 0.9 else 1e-8)
    amax = law.alpha(law.p_star) + c * W * law.p_star
    with pytest.raises(ContactLawExceeded):
        law.solve(amax * 1.0001, c)
    assert law.solve(amax, c) == pytest.approx(W * law.p_star, rel=1e-8)  # ill-conditioned at P*
