"""bouncer.Model.attractors (the library's find_attractors, run/attractors.hpp) against
independent truth:

* eps = 1/2, a = 12: one attractor, the eq. 5 family of fixed points at
  v* = 4(1+eps)/(1-eps) = 12 (a = 8(1+eps)/(p(1-eps)) with p = 2), multipliers 1 and eps^2,
  taking every start in the phase space;
* eps = 1/2, a = 24 (fig. basin2): the eq. 5 family and the period-4 sticking cycle through the
  release state (1/2, 4) (the paper; docs/guide/pictures.md, certified basins), each proved, their shares of
  the starts those of `Model.basin` over the same starts (basin classifies every start on its
  own, over 5000 + 500 steps: a different method), within a few binomial standard errors;
* the typed objects: numpy arrays, complex multipliers, labels per start.

Run by ctest (python.pytest) with PYTHONPATH=build/python.
"""

import math

import numpy as np
import pytest

import bouncer


def test_eq5_family_is_the_only_attractor():
    r = bouncer.Model(model="constant", a="12", eps="0.5").attractors(starts=(12, 8), threads=2)
    assert isinstance(r, bouncer.Attractors) and len(r.attractors) == 1
    a = r.attractors[0]
    assert isinstance(a, bouncer.Attractor)
    assert (a.kind, a.period, a.id) == ("family", 1, 0)
    vstar = 4 * (1 + 0.5) / (1 - 0.5)
    assert isinstance(a.v, np.ndarray) and a.v.dtype == np.float64 and len(a.v) >= 1
    assert np.all(np.abs(a.v - vstar) <= 1e-12 * vstar)
    # the family's multipliers: 1 (along the family) and eps^2 = 1/4
    assert sorted(a.multiplier_moduli) == pytest.approx([0.25, 1.0], abs=1e-9)
    assert all(isinstance(m, complex) for m in a.multipliers)
    assert a.certificate is not None and a.certificate["certified"] and a.certificate["outcome"] == "family"
    # every start in the phase space is in its basin
    assert r.label.shape == (8, 12) and r.label.dtype == np.int32
    inside = r.label != bouncer.Attractors.OUTSIDE
    assert inside.sum() == r.inside == a.starts and (r.label[inside] == 0).all()
    assert a.fraction == 1.0 and a.fraction_stderr == 0.0 and r.undecided == 0
    assert r.theta.shape == r.v.shape == (8, 12)
    # the starts are the cell centres of theta in [0, 1] and v in the trapping region [4, 4(1+3eps)/(1-eps)]
    assert r.v_range == ("4", "20")
    assert np.array_equal(r.theta[0], (2 * np.arange(12) + 1) / 24)


def test_eps05_a24_family_and_sticking_cycle_shares_match_basin():
    m = bouncer.Model(model="constant", a="24", eps="0.5")
    r = m.attractors(starts=(20, 15), threads=2)
    kinds = sorted(a.kind for a in r.attractors)
    assert kinds == ["family", "sticking"]
    stick = next(a for a in r.attractors if a.kind == "sticking")
    fam = next(a for a in r.attractors if a.kind == "family")
    assert stick.period == 4 and (stick.theta[0], stick.v[0]) == (0.5, 4.0)
    assert fam.period == 1 and abs(fam.v[0] - 12) <= 1e-12 * 12
    assert stick.certificate["certified"] and fam.certificate["certified"]
    n = r.inside
    assert sum(a.starts for a in r.attractors) + r.undecided == n
    for a in r.attractors:
        assert a.fraction == pytest.approx(a.starts / n, abs=1e-15)
        p = a.starts / n
        assert a.fraction_stderr == pytest.approx(math.sqrt(p * (1 - p) / n), abs=1e-15)
    # The same starts classified one by one (bouncer basin): fixed points of the family and
    # sticking with period 4, in the same shares.
    b = m.basin(grid=(20, 15), threads=2)
    names = np.array(b.classes)[b.class_]
    assert np.array_equal(b.theta, r.theta[0]) and np.array_equal(b.v, r.v[:, 0])
    inside = names != "outside"
    assert inside.sum() == n
    for a, cls in ((fam, "fixed"), (stick, "sticking")):
        share = (names == cls).sum() / n
        assert abs(a.fraction - share) <= 3 * a.fraction_stderr + 2 / n, (a.kind, a.fraction, share)


def test_bad_input_names_the_option():
    m = bouncer.Model(model="constant", a="24", eps="0.5")
    with pytest.raises(ValueError, match="cells"):
        m.attractors(starts=(4, 4), cells=(8, 8))
