"""The typed library layer (bouncer.Model and its analyses) against the CLI-parity layer
(bouncer.run and the functions on it, which test_module.py checks against the executable)
and against independent truth: the collision law worked by hand in mpmath, the paper's eq. 5
fixed points, and exact enclosures.

Run by ctest (python.pytest) with PYTHONPATH=build/python and BOUNCER_CLI=the executable,
and against a pip-installed package by tests/cli/python_pip.sh.
"""

import inspect
import json
import math
import os
import pathlib
import random
import signal
import subprocess
import threading
import time
import types
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest

import bouncer

CLI = os.environ.get("BOUNCER_CLI", str(pathlib.Path(__file__).resolve().parents[2] / "build/tools/bouncer"))
CONSTANT = dict(model="constant", a="24", eps="0.5")
TRIANGLE_DIRECTION = {0: "up", 1: "down"}


def bits_equal(x, y):
    """Two float64 arrays hold the same doubles (NaN where the other has NaN)."""
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    return x.shape == y.shape and np.array_equal(x.view(np.int64), y.view(np.int64))


def same_double(x, cli_value):
    """A double against the CLI's JSON number (or its "nan", "inf", "-inf")."""
    y = float(cli_value)
    return (math.isnan(x) and math.isnan(y)) or (x == y and math.copysign(1, x) == math.copysign(1, y))


# ---- step and orbit against the CLI's orbit ---------------------------------------------------

def orbit_matches_cli_orbit(o, r, precision, sine=False):
    """Model.orbit's arrays against bouncer.orbit's (the CLI's columns), column by column."""
    assert o.n.tolist() == r["n"].tolist()
    reals = ("theta", "v", "tau", "stuck_theta", "stuck_v")
    for name in reals:
        got = getattr(o, name)
        if precision == "double":
            assert got.dtype == np.float64 and bits_equal(got, r[name]), name
        elif precision == "interval:double":
            # Model.orbit has the double ends themselves; the CLI prints them rounded outward
            # to 17 digits, which parse back to the same double or, now and then, to the next
            # one outward (the enclosure one ulp wider).
            assert got.dtype == np.float64 and got.shape == (len(o), 2)
            for end, cli, outward in ((got[:, 0], r[name + "_lo"], -np.inf), (got[:, 1], r[name + "_hi"], np.inf)):
                nan = np.isnan(end)
                assert np.array_equal(nan, np.isnan(cli)), name
                same = end[~nan] == cli[~nan]
                one_ulp = np.nextafter(end[~nan], outward) == cli[~nan]
                assert (same | one_ulp).all() and (same.size == 0 or same.mean() > 0.8), name
        else:
            assert got.dtype.kind == "U" and got.tolist() == r[name].tolist(), name
    assert [bouncer.EVENTS[k] for k in o.event] == r["event"].tolist()
    assert o.periods.tolist() == r["periods"].tolist()
    assert o.segment.tolist() == r["segment"].tolist()
    assert o.phase_bits.tolist() == r["phase_bits"].tolist()
    assert r["wall"].tolist() == [""] + [{1: "up", -1: "down", 0: "flat"}[d] for d in o.wall[1:].tolist()]
    assert r["corner"].tolist() == [-1] + [int(c) for c in o.corner[1:]]
    assert r["flight"].tolist() == [""] + [{1: "indirect", 0: "direct", -1: "undecided"}[f] for f in o.indirect[1:]]
    sticking = [""]
    for k, (seg, passed) in enumerate(zip(o.stick_segment[1:].tolist(), o.passed_upward_turn[1:].tolist()), 1):
        if seg < 0:
            sticking.append("")
            continue
        if sine:  # the sine wall's velocity 2 pi cos(2 pi theta) where the collision stuck
            theta = float(np.mean(np.asarray(o.stuck_theta[k], dtype=np.float64)))
            direction = "up" if math.cos(2 * math.pi * theta) > 0 else "down"
        else:
            direction = TRIANGLE_DIRECTION[seg]
        sticking.append(direction + (":paper" if passed else ""))
    # (a column with no entry at all comes as int64 -1 from the CLI-parity layer)
    assert ["" if x == -1 else x for x in r["sticking"].tolist()] == sticking


@pytest.mark.parametrize("precision", ["double", "mpfr:256", "interval:double"])
@pytest.mark.parametrize("params,start", [
    (dict(model="constant", a="28.82", eps="0.96"), ("0.3", "7.5")),
    (dict(model="constant", a="20", eps="0.3"), ("0.3", "9")),  # sticks every 3 steps
    (dict(model="constant", a="8", eps="0.5", wall="sine"), ("0.5", "3")),  # the wall's direction from its velocity
])
def test_orbit_is_the_cli_orbit_bit_for_bit(precision, params, start):
    steps = 120
    m = bouncer.Model(**params, precision=precision)
    o = m.orbit(*start, steps)
    r = bouncer.orbit(**params, theta=start[0], v=start[1], steps=steps, precision=precision)
    assert (o.status, o.steps_done) == (r["end"]["status"], r["end"]["steps_done"])
    assert len(o) == o.steps_done + 1 and o.precision == precision
    if precision != "interval:double":
        assert o.status == "completed" and o.steps_done == steps
    orbit_matches_cli_orbit(o, r, precision, sine=params.get("wall") == "sine")
    if params.get("wall") == "sine":
        # The wall column is the sign of the wall's velocity 2 pi cos(2 pi theta) at the
        # impact (its one segment has no direction), here both up and down.
        theta = np.asarray(o.theta[1:], dtype=np.float64).reshape(len(o) - 1, -1).mean(axis=1)
        assert o.wall[1:].tolist() == np.where(np.cos(2 * np.pi * theta) > 0, 1, -1).tolist()
        assert set(o.wall[1:].tolist()) == {1, -1}
    if params["a"] == "20" and precision != "interval:double":
        # first sticking at step 9, then every 3 steps (the release state's period)
        sticks = np.flatnonzero(o.event == bouncer.EVENTS.index("sticking"))
        assert sticks[0] == 9 and (np.diff(sticks) == 3).all() and len(sticks) == 38


def test_orbit_every_keeps_every_kth_step_and_the_last():
    m = bouncer.Model(**CONSTANT)
    full = m.orbit(0.3, 9.5, 100)
    thin = m.orbit(0.3, 9.5, 100, every=7)
    assert thin.n.tolist() == [0] + list(range(7, 100, 7)) + [100]
    assert bits_equal(thin.v, full.v[thin.n]) and bits_equal(thin.theta, full.theta[thin.n])
    r = bouncer.orbit(**CONSTANT, theta="0.3", v="9.5", steps=100, every=7)
    assert bits_equal(thin.v, r["v"])


def test_step_is_row_one_of_the_cli_orbit():
    for params, start in [(CONSTANT, (0.3, 9.5)), (dict(model="constant", a="20", eps="0.3"), ("0.3", "9")),
                          (dict(model="veldep", a="25", c="1000"), (0.7, 13.25)),
                          # an impact where the sine wall moves down (its one segment says nothing)
                          (dict(model="constant", a="8", eps="0.5", wall="sine"), ("0.06787999488684382", "9.35200896148589"))]:
        m = bouncer.Model(**params)
        s = m.step(*start)
        r = bouncer.step(**params, theta=start[0], v=start[1])
        assert isinstance(s, bouncer.Step) and isinstance(s.theta, float)
        for name in ("theta", "v", "tau"):
            assert same_double(getattr(s, name), r[name]), name
        assert (s.event, s.periods, s.segment, s.wall, int(s.corner)) == (r["event"], r["periods"], r["segment"],
                                                                          r["wall"], r["corner"])
        assert s.indirect == (r["flight"] == "indirect")
        if s.event == "sticking":
            assert same_double(s.stuck_theta, r["stuck_theta"]) and same_double(s.stuck_v, r["stuck_v"])
            assert r["sticking"] == TRIANGLE_DIRECTION[s.stick_segment] + (":paper" if s.passed_upward_turn else "")
        else:
            assert s.stuck_theta is None and s.stick_segment is None and r["sticking"] in ("", -1)
        assert tuple(s) == (s.theta, s.v) and len(s) == 2  # theta, v = m.step(theta, v) iterates


def test_step_in_other_precisions_gives_texts_and_intervals():
    hi = bouncer.Model(**CONSTANT, precision="mpfr:256").step("0.3", "9.5")
    assert isinstance(hi.theta, str) and isinstance(hi.v, str)
    assert hi.v == bouncer.step(**CONSTANT, theta="0.3", v="9.5", precision="mpfr:256")["v"]
    box = bouncer.Model(**CONSTANT, precision="interval:128").step("0.3", "9.5")
    assert isinstance(box.v, bouncer.Interval)
    lo, hi_ = Fraction(Decimal(box.v.lo)), Fraction(Decimal(box.v.hi))
    assert lo <= Fraction(Decimal(hi.v)) <= hi_ and hi_ - lo < Fraction(1, 10**30)
    flo, fhi = box.v.to_floats()
    assert Fraction(flo) <= lo and hi_ <= Fraction(fhi)
    mp = pytest.importorskip("mpmath")
    iv = box.v.to_mpmath(bits=256)
    assert isinstance(iv, mp.ctx_iv.ivmpf) and iv.a <= mp.mpf(hi.v) <= iv.b


# ---- independent truth ----------------------------------------------------------------------

def hand_step(theta0, v0, a, eps, digits=60):
    """One impact of the constant-restitution triangle bouncer, worked by hand in mpmath:
    the flight y(t) = f(theta0) + v0 (t - theta0) - a/2 (t - theta0)^2 against the wall
    f = -1 + 4 theta on [0, 1/2), 3 - 4 theta on [1/2, 1) (period 1), the first crossing
    after theta0, and v+ = u - eps (v- - u) with u the wall's velocity there. Only for
    impacts (the test's starts do not stick)."""
    import mpmath
    with mpmath.workdps(digits):
        a, eps, t0, v0 = (mpmath.mpf(str(x)) for x in (a, eps, theta0, v0))

        def wall(phase):
            phase = phase - mpmath.floor(phase)
            return (-1 + 4 * phase, 4) if phase < 0.5 else (3 - 4 * phase, -4)

        y0 = wall(t0)[0]
        k = mpmath.floor(t0)
        start = t0
        for piece in range(400):  # linear pieces of the wall after theta0, in order
            seg_start = k + mpmath.mpf(piece) / 2
            seg_end = seg_start + mpmath.mpf(1) / 2
            if seg_end <= t0:
                continue
            h, u = wall(seg_start)
            # y(t) - (h + u (t - seg_start)) = 0 as a quadratic in s = t - t0
            c0 = y0 - h - u * (t0 - seg_start)
            c1 = v0 - u
            c2 = -a / 2
            disc = c1 * c1 - 4 * c2 * c0
            if disc < 0:
                continue
            roots = sorted([(-c1 + mpmath.sqrt(disc)) / (2 * c2), (-c1 - mpmath.sqrt(disc)) / (2 * c2)])
            for s in roots:
                t = t0 + s
                if s > mpmath.mpf(10) ** (-digits + 10) and max(start, seg_start) <= t < seg_end:
                    v_minus = v0 - a * s
                    v_plus = u - eps * (v_minus - u)
                    return t - mpmath.floor(t), v_plus, s
        raise AssertionError("no impact found")


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_step_agrees_with_the_collision_law_by_hand(seed):
    mpmath = pytest.importorskip("mpmath")
    rng = random.Random(seed)
    m = bouncer.Model(model="constant", a="28.82", eps="0.96")
    hi = bouncer.Model(model="constant", a="28.82", eps="0.96", precision="mpfr:256")
    checked = 0
    while checked < 20:
        theta, v = rng.uniform(0.01, 0.99), rng.uniform(4.5, 30)
        s = m.step(theta, v)
        if s.event != "impact":
            continue
        # the exact start is the double's exact value: Decimal(theta) is exact
        t_hand, v_hand, tau_hand = hand_step(Decimal(theta), Decimal(v), "28.82", "0.96", digits=80)
        assert abs(s.theta - t_hand) <= 1e-12 and abs(s.v - v_hand) <= 1e-12 * max(1, abs(v_hand))
        assert abs(s.tau - tau_hand) <= 1e-12
        h = hi.step(theta, v)  # the same start at 256 bits agrees with the hand step to ~1e-70
        with mpmath.workdps(80):
            assert abs(mpmath.mpf(h.v) - v_hand) < mpmath.mpf(10) ** -60 * max(1, abs(v_hand))
            assert abs(mpmath.mpf(h.theta) - t_hand) < mpmath.mpf(10) ** -60
        checked += 1


@pytest.mark.parametrize("eps,p", [("0.5", 1), ("0.6", 1), ("0.6", 2), ("0.2", 3)])
def test_eq5_fixed_points(eps, p):
    """Paper eq. 5: for a = 8(1+eps)/(p(1-eps)) every theta in (0, 1/2) (away from the wall's
    corners) is a fixed point with v* = 4(1+eps)/(1-eps) and a flight of p periods; Newton
    finds the family, with multipliers 1 (along it) and eps^2."""
    e = Fraction(eps)
    a = 8 * (1 + e) / (p * (1 - e))
    v_star = 4 * (1 + e) / (1 - e)
    a_text = str(Decimal(a.numerator) / Decimal(a.denominator)) if a.denominator != 1 else str(a.numerator)
    if Fraction(Decimal(a_text)) != a:
        pytest.skip("a is not a finite decimal")
    m = bouncer.Model(model="constant", a=a_text, eps=eps)
    for theta in (0.25, 0.375):
        s = m.step(theta, float(v_star))
        assert s.theta == pytest.approx(theta, abs=1e-13) and s.v == pytest.approx(float(v_star), rel=1e-13)
        assert s.periods == p and s.event == "impact"
    orbit = m.periodic(1, guess=("0.3", str(float(v_star) + 0.5)))
    assert orbit.converged and orbit.minimal_period == 1
    theta, v = orbit.points[0]
    assert v == pytest.approx(float(v_star), rel=1e-12) and 0 < theta < 0.5
    assert sorted(orbit.multiplier_moduli) == pytest.approx(sorted([1.0, float(e * e)]), abs=1e-9)
    assert orbit.marginal and orbit.stability == "marginal"


@pytest.mark.parametrize("a,stable", [("20", False), ("30", True)])
def test_sine_wall_period1_closed_form(a, stable):
    """The sine wall (wall="sine") through the typed layer: the classical period-1 orbit
    cos(2 pi theta*) = a (1 - eps) / (4 pi (1 + eps)), v* = a/2 (docs/guide/sine-wall.md,
    derived by hand) is a fixed point of one step of one period, and Newton's multipliers have
    the product eps^2 and are stable above a_pd = 25.8566 (eps = 1/2), not below."""
    eps = 0.5
    theta = math.acos(float(a) * (1 - eps) / (4 * math.pi * (1 + eps))) / (2 * math.pi)
    m = bouncer.Model(model="constant", a=a, eps="0.5", wall="sine")
    s = m.step(theta, float(a) / 2)
    assert s.theta == pytest.approx(theta, abs=1e-12) and s.v == pytest.approx(float(a) / 2, rel=1e-12)
    assert s.periods == 1 and s.event == "impact"
    orbit = m.periodic(1, guess=(str(round(theta, 3)), str(float(a) / 2)))
    assert orbit.converged
    moduli = orbit.multiplier_moduli
    assert moduli[0] * moduli[1] == pytest.approx(eps * eps, rel=1e-9)
    assert (max(moduli) < 1) == stable
    assert orbit.stability == ("stable" if stable else "unstable")


def test_interval_orbit_encloses_the_512_bit_orbit():
    box = bouncer.Model(**CONSTANT, precision="interval:double").orbit("0.3", "9.5", 40)
    exact = bouncer.Model(**CONSTANT, precision="mpfr:512").orbit("0.3", "9.5", 40)
    assert box.theta.shape == (41, 2) and box.lohner_fallbacks is not None
    for (lo, hi), x in zip(box.v.tolist(), exact.v.tolist()):
        assert Fraction(lo) <= Fraction(Decimal(x)) <= Fraction(hi)
    naive = bouncer.Model(**CONSTANT, precision="interval:double").orbit("0.3", "9.5", 40, method="naive")
    assert naive.lohner_fallbacks is None
    # Lohner's boxes are no wider than the naive ones at the end
    assert np.diff(box.v[-1]) <= np.diff(naive.v[-1])


def test_undecided_interval_steps():
    """An interval start whose phase straddles the triangle's corner 1/2 cannot be stepped:
    step raises bouncer.Undecided, orbit ends at once with status "undecided", as the CLI's."""
    m = bouncer.Model(**CONSTANT, precision="interval:16")
    with pytest.raises(bouncer.Undecided):
        m.step("0.4999999", "12")
    o = m.orbit("0.4999999", "12", 10)
    assert (o.status, o.steps_done, len(o)) == ("undecided", 0, 1) and o.reason
    r = bouncer.orbit(**CONSTANT, theta="0.4999999", v="12", steps=10, precision="interval:16")
    assert r["end"]["status"] == "undecided" and r["end"]["steps_done"] == 0
    assert o.reason in r["end"]["message"]
    # the same start at 64 bits is decided
    assert bouncer.Model(**CONSTANT, precision="interval:64").orbit("0.4999999", "12", 10).status == "completed"


# ---- the analyses against the CLI's -------------------------------------------------------------

def test_classify_matches_the_cli():
    for params, start in [(dict(model="constant", a="20", eps="0.3"), ("0.3", "9")),
                          (dict(model="constant", a="28", eps="0.96"), ("0.5", "4")),
                          (dict(model="elastic", a="30"), ("0.1", "20"))]:
        c = bouncer.Model(**params).classify(*start, transient=2000, steps=400)
        r = bouncer.classify(**params, theta=start[0], v=start[1], transient=2000, steps=400)
        assert c.class_ == r["class"] and c.period == r["period"] and c.evidence == r["evidence"]
        assert same_double(c.lambda_, r["lambda"])
        for key in ("transient", "steps", "max_period", "recheck_factor"):
            assert getattr(c, key) == r[key]
        for key in ("growth_alpha", "growth_per_step", "phase_branches", "accelerator_period", "accelerator_gain",
                    "growth_kind", "settled_class", "settled_at"):
            if key in r:
                assert getattr(c, key) == pytest.approx(r[key]) if isinstance(r[key], float) else getattr(c, key) == r[key]
            else:
                assert getattr(c, key) is None
    sticking = bouncer.Model(model="constant", a="20", eps="0.3").classify("0.3", "9")
    assert (sticking.class_, sticking.period) == ("sticking", 3)


def test_classify_defaults_are_the_clis():
    c = bouncer.Model(model="constant", a="20", eps="0.3").classify(0.3, 9)
    r = bouncer.classify(model="constant", a="20", eps="0.3", theta="0.3", v="9")
    assert (c.transient, c.steps, c.max_period, c.recheck_factor) == (5000, 500, 64, 20)
    assert (c.transient, c.steps, c.max_period, c.recheck_factor) == (r["transient"], r["steps"], r["max_period"],
                                                                      r["recheck_factor"])


def test_lyapunov_matches_the_cli_with_its_defaults():
    m = bouncer.Model(model="constant", a="28", eps="0.96")
    ly = m.lyapunov("0.5", "4")
    r = bouncer.lyapunov(model="constant", a="28", eps="0.96", theta="0.5", v="4")
    assert (ly.transient, ly.steps, ly.blocks) == (1000, 10000, 20) == (r["transient"], r["steps"], r["blocks"])
    for key, cli_key in (("lambda_", "lambda"), ("stderr", "stderr"), ("growth_alpha", "growth_alpha"),
                         ("v_max", "v_max")):
        assert same_double(getattr(ly, key), r[cli_key]), key
    assert (ly.contracted, ly.unbounded, ly.undecided, ly.note) == (r["contracted"], r["unbounded"], r["undecided"],
                                                                    r["note"])
    stuck = bouncer.Model(model="constant", a="20", eps="0.3").lyapunov(0.3, 9, transient=10, steps=100)
    assert stuck.contracted and stuck.lambda_ == -math.inf


def test_lyapunov_curve_starts_where_the_cli_starts():
    """The exponent curve's default start is the CLI's (0.1, wall speed + 2), not the
    single-orbit default (0.5, 4) (issue 22: the Python layer started curves at (0.5, 4))."""
    curve = dict(model="constant", eps="0.5", a="15", vary="a", range=("10", "20"), samples=3, steps=300,
                 transient=100)
    r = bouncer.lyapunov(**curve, threads=1)
    assert r["summary"]["starts"][0] == ["0.1", "6"]
    words = bouncer._words("lyapunov", dict(curve, quiet=True, json=True))[1:]
    p = subprocess.run([CLI, *words], capture_output=True, text=True, check=True)
    assert json.loads(p.stdout)["summary"]["starts"] == r["summary"]["starts"]
    assert r["table"]["theta0"].tolist() == [0.1] * 3 and r["table"]["v0"].tolist() == [6.0] * 3
    # the single-orbit exponent keeps its default start, the release state
    assert bouncer.lyapunov(model="constant", eps="0.5", a="15", steps=100)["provenance"]["inputs"]["theta"] == "0.5"


def test_periodic_matches_the_cli():
    for opts in (dict(period=1, guess=("0.3", "12")), dict(period=2), dict(period=3, guess=("0.3", "9"))):
        params = CONSTANT if opts["period"] != 3 else dict(model="constant", a="20", eps="0.3")
        p = bouncer.Model(**params).periodic(**opts)
        r = bouncer.periodic(**params, **opts)
        assert p.converged == r["converged"] and p.minimal_period == r["minimal_period"]
        assert [tuple(map(float, pt)) for pt in r["points"]] == p.points
        if r["converged"]:
            assert [tuple(map(float, mu)) for mu in r["multipliers"]] == p.multipliers
            assert all(same_double(x, y) for x, y in zip(p.multiplier_moduli, r["multiplier_moduli"]))
        else:  # no orbit, so no multipliers and no events (not the last iterate's)
            assert r["multipliers"] is None and p.multipliers is None and p.multiplier_moduli is None
            assert r["events"] == [] and p.events == []
        assert (p.events, p.wall_periods, p.iterations, p.note, p.marginal, p.complex_pair, p.stability) == (
            r["events"], r["wall_periods"], r["iterations"], r["note"], r["marginal"], r["complex_pair"], r["stability"])
        assert same_double(p.residual, r["residual"]) and same_double(p.tolerance, r["tolerance"])


def test_periodic_at_256_bits_gives_texts_that_agree_with_double():
    p = bouncer.Model(**CONSTANT, precision="mpfr:256").periodic(1, guess=("0.3", "12"))
    d = bouncer.Model(**CONSTANT).periodic(1, guess=("0.3", "12"))
    assert isinstance(p.points[0][1], str)
    assert float(p.points[0][1]) == pytest.approx(d.points[0][1], rel=1e-14)
    r = bouncer.periodic(**CONSTANT, period=1, guess=("0.3", "12"), precision="mpfr:256")
    assert [list(pt) for pt in p.points] == r["points"]


def test_continue_branch_end_estimate_matches_the_cli():
    # The sticking threshold a* = 200/9 at eps = 1/4 (closed form, tests/test_continuation.cpp):
    # its error estimate's widened bracket contains it, with the CLI's digits.
    model = dict(model="constant", a="26", eps="0.25")
    opts = dict(period=1, guess=("0.5", "4"), range=("20", "31"))
    low = bouncer.Model(**model).continue_branch(**opts).low
    cli_low = bouncer.continue_branch(**model, **opts)["summary"]["low"]
    acc = low.accuracy
    assert acc["kind"] == "estimate" == cli_low["accuracy"]
    lo, hi = (Fraction(x) for x in acc["bracket_estimate"])
    assert lo <= Fraction(200, 9) <= hi
    assert list(acc["bracket_estimate"]) == cli_low["bracket_estimate"]
    assert (acc["a_star_backed"], acc["a_star_plus_minus"], acc["a_star_digits"]) == (
        cli_low["a_star_backed"], cli_low["a_star_plus_minus"], cli_low["a_star_digits"])
    assert low.param == float(cli_low["param"])  # the computed value is kept


def test_continue_branch_matches_the_cli():
    opts = dict(period=1, guess=("0.3", "12"), vary="eps", range=("0.45", "0.55"))
    b = bouncer.Model(**CONSTANT).continue_branch(**opts)
    r = bouncer.continue_branch(**CONSTANT, **opts)["summary"]
    assert len(b.param) == r["points"] and b.param.dtype == np.float64
    assert same_double(b.param[0], r["param_min"]) and same_double(b.param[-1], r["param_max"])
    assert b.theta.shape == b.v.shape == (len(b.param), 1)
    start = r["start"]
    assert same_double(b.param[b.start], start["param"]) and b.events[b.start] == start["events"]
    assert [float(b.theta[b.start, 0]), float(b.v[b.start, 0])] == [float(x) for x in start["points"][0]]
    assert b.stability[b.start] == start["stability"]
    for end, cli_end in ((b.low, r["low"]), (b.high, r["high"])):
        assert isinstance(end, bouncer.BranchEnd)
        assert end.reason == cli_end["reason"] and same_double(end.param, cli_end["param"])
        assert [float(x) for x in end.bracket] == [float(x) for x in cli_end["bracket"]]
        assert (end.margin, end.impact, end.knot, end.detail) == (cli_end["margin"], cli_end["impact"],
                                                                  cli_end["knot"], cli_end["detail"])
        # The error estimate: the same digits and widened bracket as the CLI's.
        assert end.accuracy["kind"] == cli_end["accuracy"]
        for key in ("a_star_backed", "a_star_plus_minus", "a_star_digits", "refined_param", "refined_bits"):
            assert end.accuracy.get(key) == cli_end.get(key), key
        if "bracket_estimate" in cli_end:
            assert list(end.accuracy["bracket_estimate"]) == cli_end["bracket_estimate"]
        if cli_end["beyond"] is None:
            assert end.beyond is None
        else:
            by, cb = end.beyond, cli_end["beyond"]
            assert same_double(by["param"], cb["param"]) and by["class_"] == cb["class"]
            assert (by["period"], by["evidence"], by["newton_orbit_events"]) == (cb["period"], cb["evidence"],
                                                                                cb["newton_orbit_events"])
            assert by["newton_orbit_relation"] == cb["newton_orbit_relation"]
    assert len(b.bifurcations) == len(r["bifurcations"])
    assert b.corrector_runs == r["corrector_runs"]


def test_certify_sticking_matches_the_cli():
    m = bouncer.Model(model="constant", a="28.82", eps="0.96")
    c = m.certify_sticking(max_steps=2000)
    r = bouncer.certify_sticking(model="constant", a="28.82", eps="0.96", max_steps=2000)
    assert c.certified is True
    for key in ("certified", "outcome", "period", "scalar", "bits", "steps_checked", "statement", "double_period",
                "attractor", "lohner_fallbacks"):
        assert getattr(c, key) == r[key], key
    assert [{k: v for k, v in a.items() if k != "seconds"} for a in c.attempts] == \
           [{k: v for k, v in a.items() if k != "seconds"} for a in r["attempts"]]
    assert (c.max_steps, c.schedule) == (2000, r["schedule"])
    # the CLI's defaults: the release state, 100000 steps, interval:double then up to 4096 bits
    assert m.certify_sticking(max_steps=10).schedule == r["schedule"]


def test_certify_sticking_sticks_with_the_exact_release():
    """From (0.3, 9) at a = 20, eps = 0.3 the orbit first sticks at step 9 (as Model.orbit
    shows), then from the release state every 3 steps."""
    m = bouncer.Model(model="constant", a="20", eps="0.3")
    c = m.certify_sticking("0.3", "9", max_steps=100)
    assert (c.certified, c.outcome, c.period, c.double_period) == (True, "sticks", 9, 9)
    assert (c.release_theta, c.release_v) == ("0.5", "4")  # the triangle's release state, exactly
    release = m.certify_sticking(max_steps=100)  # the default start is the release state
    assert (release.certified, release.outcome, release.period) == (True, "sticks", 3)


def test_certify_chaos_matches_the_cli_and_its_certificate_replays():
    # veldep c = 1000, a = 27: the horseshoe of claims row 12. The typed call and the command
    # line give the same bound; the certificate replays valid in Arb through Python, and a
    # certificate with one h-set moved does not; malformed text is a ValueError naming the field.
    proof = bouncer.Model(model="veldep", a="27", c="1000").certify_chaos()
    assert proof.certified and proof.replay_valid
    assert 0 < proof.bound_double < 0.2 and proof.k == 2 and proof.hsets >= 3
    assert proof.saddle["period"] == 2 and abs(proof.saddle["lambda_u"] + 2.87) < 0.01
    assert "Not proved: that the attractor is this set" in proof.statement
    r = json.loads(bouncer.run("certify-chaos", model="veldep", a="27", c="1000", json=True))
    assert r["entropy"]["bound"] == proof.bound and r["certified"] is True
    check = bouncer.check_certificate(proof.certificate)
    assert check.valid and check.disjoint and check.bound == proof.bound
    assert all(ok for ok, _ in check.coverings) and check.problems == ["valid"]
    doc = json.loads(proof.certificate)
    p, q = (doc["sets"][2]["centre"][1].split("/") + ["1"])[:2]
    doc["sets"][2]["centre"][1] = f"{int(p) + int(q) // 100}/{q}"  # v moved by 0.01
    moved = bouncer.check_certificate(json.dumps(doc))
    assert not moved.valid  # the moved set meets a neighbour or is no longer covered
    assert any("may intersect" in p or "not proved" in p for p in moved.problems), moved.problems
    with pytest.raises(ValueError, match=r"^k: must be an integer"):
        bouncer.check_certificate(proof.certificate.replace('"k": 2', '"k": 0'))
    with pytest.raises(ValueError, match=r"^bits: "):
        bouncer.check_certificate(proof.certificate, bits=8)
    none = bouncer.Model(model="veldep", a="20", c="1000").certify_chaos()
    assert not none.certified and none.bound is None and none.certificate is None
    assert "no saddle periodic orbit found" in none.statement


def test_certify_periodic_matches_the_cli():
    m = bouncer.Model(model="constant", a="20", eps="0.3")
    for opts in (dict(period=1, guess=("0.3", "9")), dict(period=3, guess=("0.3", "9"))):
        c = m.certify_periodic(**opts)
        r = bouncer.certify_periodic(model="constant", a="20", eps="0.3", **opts)
        for key in ("certified", "outcome", "statement", "bits", "period", "minimal_period"):
            assert getattr(c, key) == r.get(key), key
        if c.certified:
            assert c.stability == r["stability"] and c.events == r["events"]
            assert [(p[0].lo, p[0].hi, p[1].lo, p[1].hi) for p in c.points] == \
                   [(p["theta"][0], p["theta"][1], p["v"][0], p["v"][1]) for p in r["points"]]
            for key, value in r["multipliers"].items():
                got = c.multipliers[key]
                assert (got == value) if key == "kind" else [got.lo, got.hi] == value, key
        else:
            assert c.reason == r["reason"]
    family = bouncer.Model(**CONSTANT).certify_periodic(1, guess=("0.3", "12"))
    assert family.certified and family.outcome == "family" and family.family is not None
    lo, hi = (Fraction(Decimal(x)) for x in (family.family["parameter_at_theta"].lo,
                                              family.family["parameter_at_theta"].hi))
    assert lo <= 24 <= hi  # eq. 5: a = 8 (1 + eps) / (1 - eps) = 24 at eps = 1/2


# ---- bad input: bouncer's message, as in the CLI-parity layer -------------------------------------

IC = dict(theta="0.25", v="12")
BAD_MODELS = [
    dict(model="constant", a="0", eps="0.5"),
    dict(model="constant", a=-1, eps=0.5),
    dict(model="constant", a="1e10", eps="0.5"),
    dict(model="constant", a="24", eps="1.5"),
    dict(model="constant", a="24", eps="1.0000000000000000000000001"),
    dict(model="elastic", a="24", eps="0.5"),
    dict(model="veldep", a="24", c="0"),
    dict(model="constant", a=float("nan"), eps="0.5"),
    dict(model="constant", a="24", eps=float("inf")),
    dict(model="foo", a="24"),
    dict(model="constant", a="24", eps="0.5", wall="asymmetric:1.5"),
    dict(model="constant", a="24", eps="0.5", precision="float"),
    dict(model="constant", a="24", eps="0.5", precision="mpfr:8"),
    dict(model="constant", a="24"),
    dict(model="veldep", a="24"),
    dict(model="constant", a="24\x00junk", eps="0.5"),
    dict(model="constant", a="24", eps="0.5", veldep_collapse=True),
]


@pytest.mark.parametrize("params", BAD_MODELS, ids=[repr(p) for p in BAD_MODELS])
def test_bad_model_raises_the_cli_message(params):
    cli_params = {k: "on" if v is True else v for k, v in params.items()}  # the CLI's --veldep-collapse on
    with pytest.raises(ValueError) as cli_error:
        bouncer.orbit(**cli_params, **IC, steps=1)
    with pytest.raises(ValueError) as model_error:
        bouncer.Model(**params)
    assert str(model_error.value) == str(cli_error.value)
    assert str(model_error.value).split(":")[0] in ("a", "eps", "c", "model", "wall", "precision", "veldep-collapse")


BAD_CALLS = [
    ("step", CONSTANT, dict(theta="1", v="12"), "orbit", dict(theta="1", v="12", steps=1)),
    ("step", CONSTANT, dict(theta=0.25, v=3.9), "orbit", dict(theta=0.25, v=3.9, steps=1)),
    ("step", CONSTANT, dict(theta=0.25, v=1e16), "orbit", dict(theta=0.25, v=1e16, steps=1)),
    ("step", CONSTANT, dict(theta=float("nan"), v=12.0), "orbit", dict(theta=float("nan"), v=12.0, steps=1)),
    ("step", CONSTANT, dict(theta=0.5, v=-4.0001), "orbit", dict(theta=0.5, v=-4.0001, steps=1)),
    ("orbit", CONSTANT, dict(theta="0.25", v="12", steps=-1), "orbit", dict(**IC, steps=-1)),
    ("orbit", CONSTANT, dict(theta="0.25", v="12", steps="1.5"), "orbit", dict(**IC, steps="1.5")),
    ("orbit", CONSTANT, dict(theta="0.25", v="12", steps=3, every=0), "orbit", dict(**IC, steps=3, every=0)),
    ("orbit", CONSTANT, dict(theta="0.25", v="12", steps=3, method="lohner"), "orbit",
     dict(**IC, steps=3, method="lohner")),
    ("classify", dict(CONSTANT, precision="interval:64"), dict(theta="0.25", v="12"), "classify",
     dict(**IC, precision="interval:64")),
    ("classify", CONSTANT, dict(theta="0.25", v="12", steps=4), "classify", dict(**IC, steps=4)),
    ("classify", CONSTANT, dict(theta="0.25", v="12", max_period=300), "classify", dict(**IC, max_period=300)),
    ("lyapunov", CONSTANT, dict(theta="0.25", v="12", steps=-5), "lyapunov", dict(**IC, steps=-5)),
    ("lyapunov", CONSTANT, dict(theta="0.25", v="12", blocks=0), "lyapunov", dict(**IC, blocks=0)),
    ("periodic", CONSTANT, dict(period=0, guess=("0.3", "12")), "periodic", dict(period=0, guess=("0.3", "12"))),
    ("periodic", CONSTANT, dict(period=1, guess=("0.3", "2")), "periodic", dict(period=1, guess=("0.3", "2"))),
    ("periodic", CONSTANT, dict(period=1, max_iter=0), "periodic", dict(period=1, max_iter=0)),
    ("continue_branch", CONSTANT, dict(period=1, guess=("0.3", "12"), vary="q", range=("1", "2")), "continue_branch",
     dict(period=1, guess=("0.3", "12"), vary="q", range=("1", "2"))),
    ("continue_branch", CONSTANT, dict(period=1, guess=("0.3", "12"), vary="c", range=("1", "2")), "continue_branch",
     dict(period=1, guess=("0.3", "12"), vary="c", range=("1", "2"))),
    ("continue_branch", CONSTANT, dict(period=1, guess=("0.3", "12"), range=("25", "30")), "continue_branch",
     dict(period=1, guess=("0.3", "12"), range=("25", "30"), a="24")),
    ("continue_branch", CONSTANT, dict(period=1, guess=("0.3", "12"), vary="eps", range=("0.4", "1.5")),
     "continue_branch", dict(period=1, guess=("0.3", "12"), vary="eps", range=("0.4", "1.5"))),
    ("certify_sticking", CONSTANT, dict(max_bits=8), "certify_sticking", dict(max_bits=8)),
    ("certify_sticking", CONSTANT, dict(start_bits="fast"), "certify_sticking", dict(start_bits="fast")),
    ("certify_sticking", CONSTANT, dict(theta="0.25", v="2"), "certify_sticking", dict(theta="0.25", v="2")),
    ("certify_sticking", dict(model="veldep", a="25", c="1000"), dict(), "certify_sticking", dict()),
    ("certify_periodic", CONSTANT, dict(period=1, guess=("0.3", "12"), max_bits=1), "certify_periodic",
     dict(period=1, guess=("0.3", "12"), max_bits=1)),
    ("certify_periodic", CONSTANT, dict(period=0), "certify_periodic", dict(period=0)),
    ("certify_periodic", CONSTANT, dict(period=1, vary="c"), "certify_periodic", dict(period=1, vary="c")),
]


@pytest.mark.parametrize("method,params,args,function,cli_args", BAD_CALLS,
                         ids=[f"{m}:{sorted(a.items())}" for m, _, a, _, _ in BAD_CALLS])
def test_bad_call_raises_the_cli_message(method, params, args, function, cli_args):
    cli_params = {k: v for k, v in params.items() if k not in cli_args}
    with pytest.raises(ValueError) as cli_error:
        getattr(bouncer, function)(**cli_params, **cli_args)
    m = bouncer.Model(**params)
    with pytest.raises(ValueError) as model_error:
        if method == "step":
            m.step(args["theta"], args["v"])
        else:
            getattr(m, method)(**args)
    assert str(model_error.value) == str(cli_error.value)


def test_wrong_types_and_keywords_are_type_errors():
    m = bouncer.Model(**CONSTANT)
    with pytest.raises(TypeError):
        m.step(True, 12.0)
    with pytest.raises(TypeError):
        m.step([0.25], 12.0)
    with pytest.raises(TypeError):
        bouncer.Model(model="constant", a="24", epss="0.5")
    with pytest.raises(TypeError):
        m.classify(0.25, 12, transient_steps=10)


def test_fast_double_path_equals_the_exact_path():
    """Model.step in double takes a float as it is when double comparisons prove the start
    valid; every other start goes through the exact decimal validation. Both must give the
    same answer, the same Step or the same error, also next to knots and the wall's speed."""
    rng = random.Random(7)
    for wall in ("triangle", "asymmetric:0.3", "knots:0:0,0.1:1,0.7:-1"):
        m = bouncer.Model(model="constant", a="24", eps="0.5", wall=wall)
        knots = [0.0, 0.5] if wall == "triangle" else [0.0, 0.3] if wall.startswith("asym") else [0.0, 0.1, 0.7]
        starts = [(rng.random(), rng.uniform(-12, 30)) for _ in range(300)]
        for k in knots:
            for theta in (k, np.nextafter(k, 1), np.nextafter(k, -1) if k > 0 else 0.0):
                for v in (-10.0, -4.0, 4.0, 10.0, 20 / 3, -20 / 7, 2 / 0.3):
                    starts.append((float(theta), float(v)))
        for theta, v in starts:
            try:
                fast = m.step(theta, v)
                fast = (fast.theta, fast.v, fast.event, fast.tau, fast.segment)
            except ValueError as e:
                fast = str(e)
            try:
                exact = m.step(Decimal(theta), Decimal(v))
                exact = (exact.theta, exact.v, exact.event, exact.tau, exact.segment)
            except ValueError as e:
                exact = str(e)
            assert fast == exact, (wall, theta, v)


def test_floats_are_exact_binary_values_and_strings_exact_decimals():
    d = bouncer.Model(model="constant", a=28.82, eps=0.96)
    assert d.a == str(Decimal(28.82)) and d.eps == str(Decimal(0.96))
    s = bouncer.Model(model="constant", a="28.82", eps="0.96")
    assert s.a == "28.82"
    # the same double in double precision ...
    assert bits_equal(d.orbit(0.3, 7.5, 5).v, s.orbit(0.3, 7.5, 5).v)
    # ... and different numbers at 256 bits
    hi_d = bouncer.Model(model="constant", a=28.82, eps=0.96, precision="mpfr:256").orbit(0.3, 7.5, 5)
    hi_s = bouncer.Model(model="constant", a="28.82", eps="0.96", precision="mpfr:256").orbit(0.3, 7.5, 5)
    assert hi_d.v[5] != hi_s.v[5]
    assert bouncer.Model(model="constant", a=Decimal("28.82"), eps="0.96").a == "28.82"


# ---- the GIL, interrupts, threads --------------------------------------------------------------

def test_ctrl_c_interrupts_a_long_orbit_and_the_model_stays_usable():
    m = bouncer.Model(model="constant", a="28.82", eps="0.96")
    timer = threading.Timer(0.3, os.kill, args=(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        m.orbit(0.3, 7.5, 10**12, every=10**9)  # hours of steps
    assert time.monotonic() - t0 < 10
    timer.cancel()
    assert m.step(0.3, 7.5).event == "impact"


def test_two_threads_run_orbits_at_the_same_time():
    m = bouncer.Model(model="constant", a="28.82", eps="0.96")
    n = 3 * 10**6
    t0 = time.monotonic()
    m.orbit(0.3, 7.5, n, every=n)
    alone = time.monotonic() - t0
    spans = {}
    barrier = threading.Barrier(2)

    def work(k):
        barrier.wait()
        t = time.monotonic()
        m.orbit(0.3, 7.5, n, every=n)
        spans[k] = (t, time.monotonic())

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    (a0, a1), (b0, b1) = spans[0], spans[1]
    assert a0 < b1 and b0 < a1 and alone > 0.05  # they overlapped: the GIL was released


# ---- the package: namespace, types, documentation, version ----------------------------------------

def test_namespace_is_clean_and_all_is_complete():
    public = [n for n in dir(bouncer) if not n.startswith("_")]
    assert sorted(public) == sorted(bouncer.__all__)
    for name in bouncer.__all__:
        assert not isinstance(getattr(bouncer, name), types.ModuleType), name
    for leaked in ("np", "csv", "json", "shlex", "Decimal", "Integral", "Real_", "annotations", "dataclasses"):
        assert leaked not in public


def test_typed_and_documented():
    sig = inspect.signature(bouncer.Model.__init__)
    for name in ("model", "a", "eps", "c", "wall", "downward_sticking", "veldep_collapse", "precision"):
        assert sig.parameters[name].kind is inspect.Parameter.KEYWORD_ONLY
        assert sig.parameters[name].annotation is not inspect.Parameter.empty
        assert name in bouncer.Model.__doc__
    for method in ("orbit", "classify", "lyapunov", "periodic", "continue_branch", "certify_sticking",
                   "certify_periodic"):
        f = getattr(bouncer.Model, method)
        sig = inspect.signature(f)
        assert sig.return_annotation is not inspect.Signature.empty, method
        for name, p in sig.parameters.items():
            if name == "self":
                continue
            assert p.annotation is not inspect.Parameter.empty, (method, name)
            assert name in f.__doc__, (method, name)  # every parameter, with its range
    assert "theta" in bouncer.Model.step.__doc__ and "1e15" in bouncer.Model.step.__doc__
    for cls in (bouncer.Classification, bouncer.Lyapunov, bouncer.PeriodicOrbit, bouncer.Branch,
                bouncer.StickingCertificate, bouncer.PeriodicCertificate):
        assert cls.__annotations__ and cls.__doc__
    stub = pathlib.Path(bouncer.__file__).with_name("_core.pyi")
    assert stub.is_file() and "class Step" in stub.read_text()
    assert pathlib.Path(bouncer.__file__).with_name("py.typed").is_file()


def test_version_is_the_clis():
    p = subprocess.run([CLI, "--version"], capture_output=True, text=True, check=True)
    assert p.stdout.split()[0] == "bouncer" and bouncer.__version__ == p.stdout.split()[1]


def test_repr_and_properties():
    m = bouncer.Model(model="veldep", a="25", c="1000", precision="mpfr:128")
    assert repr(m) == "bouncer.Model(a='25', c='1000', model='veldep', precision='mpfr:128')"
    assert (m.model, m.a, m.eps, m.c, m.wall, m.precision, m.bits) == ("veldep", "25", None, "1000", "triangle",
                                                                       "mpfr:128", 128)
    m = bouncer.Model(**CONSTANT)
    s = m.step(0.375, 12.0)
    assert repr(s) == f"bouncer.Step(theta={s.theta!r}, v={s.v!r})"
    theta, v = 0.3, 9.5
    for _ in range(5):
        theta, v = m.step(theta, v)  # the step is the state: iterating the map
    assert (theta, v) == tuple(m.orbit(0.3, 9.5, 5).theta[-1:]) + tuple(m.orbit(0.3, 9.5, 5).v[-1:])


def test_continue_branch_certify_proves_the_ends_against_closed_forms():
    """continue_branch(certify=True), as `continue --certify`: the period-1 sticking orbit
    through (1/2, 4) at eps = 1/4 lives exactly for 200/9 <= a < 32 (the sticking threshold
    and the knot theta = 0: closed forms), so the low end's enclosure holds 200/9 and the
    high end's 32 (exact fractions); the eps = 0.9 period-11 fold's other multiplier is
    det DP^11 = 0.9^22 (area contraction eps^2 per impact). Without certify: None."""
    from fractions import Fraction as F
    m = bouncer.Model(model="constant", eps="0.25", a="26")
    b = m.continue_branch(1, ("0.5", "4"), ("20", "33.5"), certify=True)
    for end, truth in ((b.low, F(200, 9)), (b.high, F(32))):
        c = end.certified
        assert c is not None and c["kind"] == "border" and c["certified"], c
        assert F(c["enclosure"].lo) <= truth <= F(c["enclosure"].hi) and c["width"] < 1e-30
    assert m.continue_branch(1, ("0.5", "4"), ("20", "33.5")).low.certified is None
    f = bouncer.Model(model="constant", eps="0.9", a="12.5").continue_branch(
        11, ("0.04780185758554826", "34.63889719838767"), ("12", "13"), certify=True)
    assert f.low.reason == "fold"
    c = f.low.certified
    assert c is not None and c["kind"] == "smooth" and c["certified"], c
    assert F(c["other_multiplier"].lo) <= F(9, 10) ** 22 <= F(c["other_multiplier"].hi)


def test_sine_wall_branch_and_attractors():
    """continue_branch and attractors on the sine wall through the typed layer, against the
    closed forms at eps = 1/2 (docs/guide/sine-wall.md): the stable period-1 branch from a = 30
    ends in the saddle-node a_sn = 4 pi (1 + eps)/(1 - eps) = 12 pi and period-doubles at
    a_pd = 4 pi^2 (1 + eps)^2 / sqrt(4 (1 + eps^2)^2 + pi^2 (1 - eps^2)^2); at a = 30 the
    attractors are the focus (theta*, a/2) and the period-1 sticking cycle through the release
    state (theta_r, 2 pi cos 2 pi theta_r), theta_r = asin(a / 4 pi^2) / (2 pi), both certified."""
    eps, a = 0.5, 30.0
    m = bouncer.Model(model="constant", a="30", eps="0.5", wall="sine")
    b = m.continue_branch(1, ("0.1", "15"), ("20", "39"))
    assert b.high.reason == "fold" and b.high.param == pytest.approx(12 * math.pi, rel=1e-9)
    a_pd = 4 * math.pi ** 2 * (1 + eps) ** 2 / math.sqrt(4 * (1 + eps ** 2) ** 2 + math.pi ** 2 * (1 - eps ** 2) ** 2)
    assert [x["kind"] for x in b.bifurcations] == ["period_doubling"]
    assert b.bifurcations[0]["param"] == pytest.approx(a_pd, rel=1e-10)
    found = {x.kind: x for x in m.attractors(starts=(30, 30)).attractors}
    assert set(found) == {"periodic", "sticking"}
    theta_star = math.acos(a * (1 - eps) / (4 * math.pi * (1 + eps))) / (2 * math.pi)
    theta_r = math.asin(a / (4 * math.pi ** 2)) / (2 * math.pi)
    focus, cycle = found["periodic"], found["sticking"]
    assert focus.theta[0] == pytest.approx(theta_star, abs=1e-12) and focus.v[0] == pytest.approx(a / 2, rel=1e-12)
    assert cycle.theta[0] == pytest.approx(theta_r, abs=1e-12)
    assert cycle.v[0] == pytest.approx(2 * math.pi * math.cos(2 * math.pi * theta_r), rel=1e-12)
    assert focus.certificate["certified"] and cycle.certificate["certified"]
