"""The typed orbit grids of bouncer.Model (portrait and lyapunov_curve: the library's run/
calls) against the CLI-parity layer (bouncer.run("portrait", ...) and
bouncer.lyapunov(vary=...), which run the command in-process), and against independent
truth: the eq. 5 fixed point (eps = 1/2, a = 24: (1/4, 12) is fixed; its multipliers are 1
and eps^2, so its exponent is 0), the release state (1/2, 4), which sticks with period 1 for
200/9 <= a < 32 at eps = 1/4 (a contracting step: lambda = -inf), and an elastic flight at
a = 1e-300 from v = 1e15, 2e315 periods long, which no double can hold (undecided).

Run by ctest (python.pytest) with PYTHONPATH=build/python.
"""

import math

import numpy as np
import pytest

import bouncer


def bits_equal(x, y):
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    return x.shape == y.shape and np.array_equal(x.view(np.int64), y.view(np.int64))


def cli_rows(text):
    """The CSV rows the command printed (without its provenance comments)."""
    lines = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    return [ln.split(",") for ln in lines[1:]], [ln for ln in text.splitlines() if ln.startswith("# undecided")]


@pytest.fixture(scope="module")
def fixed():
    return bouncer.Model(model="constant", a="24", eps="0.5")


# ---- portraits ------------------------------------------------------------------------------

def test_portrait_is_the_commands(fixed):
    p = fixed.portrait(["0.25", "0.3", "0.1"], ["12", "9.5", "6"], steps=40)
    rows, _ = cli_rows(bouncer.run("portrait", model="constant", a="24", eps="0.5", theta="0.25,0.3,0.1",
                                   v="12,9.5,6", steps=40, quiet=True))
    assert len(rows) == len(p.n) == 3 * 41
    assert (p.orbit == [int(r[0]) for r in rows]).all() and (p.n == [int(r[1]) for r in rows]).all()
    assert bits_equal(p.theta, [float(r[2]) for r in rows]) and bits_equal(p.v, [float(r[3]) for r in rows])
    assert [bouncer.EVENTS[e] for e in p.event] == [r[4] for r in rows]
    assert p.starts == [("0.25", "12"), ("0.3", "9.5"), ("0.1", "6")]
    assert p.theta_text is None and p.undecided == []


def test_portrait_at_200_bits_prints_the_commands_digits():
    m = bouncer.Model(model="veldep", a="27", c="1000", precision="mpfr:200")
    p = m.portrait("0.3", "6", steps=30, transient=5)
    rows, _ = cli_rows(bouncer.run("portrait", model="veldep", a="27", c="1000", theta="0.3", v="6", steps=30,
                                   transient=5, precision="mpfr:200", quiet=True))
    assert p.theta_text == [r[2] for r in rows] and p.v_text == [r[3] for r in rows]
    assert (p.n == np.arange(6, 36)).all()  # no start row after a transient


def test_portrait_on_the_fixed_point_stays(fixed):
    p = fixed.portrait("0.25", "12", steps=25)
    assert bouncer.EVENTS[p.event[0]] == "start" and (p.n == np.arange(26)).all()
    assert np.allclose(p.theta, 0.25, atol=1e-12) and np.allclose(p.v, 12, atol=1e-10)
    assert all(bouncer.EVENTS[e] == "impact" for e in p.event[1:])


def test_portrait_of_the_release_state_sticks_every_step():
    p = bouncer.Model(model="constant", a="24", eps="0.25").portrait("0.5", "4", steps=8)
    assert (p.theta[1:] == 0.5).all() and (p.v[1:] == 4).all()
    assert all(bouncer.EVENTS[e] == "sticking" for e in p.event[1:])


def test_portrait_undecided_orbit_is_the_commands():
    m = bouncer.Model(model="elastic", a="1e-300")
    p = m.portrait(["0.1", "0.2"], ["1e15", "5"], steps=6)
    assert p.undecided[0][:2] == (0, 1) and len(p.undecided) == 1
    assert (p.orbit == 0).sum() == 1 and (p.orbit == 1).sum() == 7
    rows, undecided = cli_rows(bouncer.run("portrait", model="elastic", a="1e-300", theta="0.1,0.2", v="1e15,5",
                                           steps=6, quiet=True))
    assert undecided == [f"# undecided: orbit 0 step 1: {p.undecided[0][2]}"]
    assert bits_equal(p.v, [float(r[3]) for r in rows])


def test_portrait_threads_do_not_change_it():
    m = bouncer.Model(model="veldep", a="27", c="1000")
    one = m.portrait(["0.3", "0.1", "0.7"], ["6", "9", "12"], steps=200, threads=1)
    two = m.portrait(["0.3", "0.1", "0.7"], ["6", "9", "12"], steps=200, threads=2)
    assert bits_equal(one.theta, two.theta) and bits_equal(one.v, two.v) and (one.event == two.event).all()


# ---- exponent curves ------------------------------------------------------------------------

CURVE = dict(range=(20, 30), samples=7, ics=2, theta="0.3", v="6", transient=300, steps=1500)


def test_curve_is_the_commands():
    c = bouncer.Model(model="veldep", a="20", c="1000").lyapunov_curve(**CURVE)
    r = bouncer.lyapunov(model="veldep", c="1000", vary="a", **CURVE)
    t = r["table"]
    assert c.lambda_.shape == (7, 2) and c.class_.shape == (7, 2)
    assert bits_equal(c.lambda_.ravel(), np.array(t["lambda"], dtype=float))
    assert bits_equal(c.stderr.ravel(), np.array(t["stderr"], dtype=float))
    assert bits_equal(np.repeat(c.value, 2), t["value"])
    assert [c.classes[k] for k in c.class_.ravel()] == list(t["class"])
    assert (c.period.ravel() == t["period"]).all()
    assert c.starts == [tuple(s) for s in r["summary"]["starts"]]
    assert c.values[0] == "20" and c.values[-1] == "30"
    for k, v in enumerate(r["summary"]["values"]):  # the CLI's JSON per value
        assert v["value"] == c.values[k] and v["max_lambda"] == c.max_lambda[k]


def test_curve_value_is_the_single_point_exponent():
    c = bouncer.Model(model="veldep", a="20", c="1000").lyapunov_curve(**CURVE)
    for k in (1, 4):  # 20 + 10/6 and 20 + 40/6: not exact decimals
        m = bouncer.Model(model="veldep", a=c.values[k], c="1000")
        for j, (theta, v) in enumerate(c.starts):
            one = m.lyapunov(theta, v, transient=300, steps=1500)
            assert bits_equal(c.lambda_[k, j], one.lambda_) and bits_equal(c.stderr[k, j], one.stderr)


def test_curve_at_the_fixed_point_is_marginal(fixed):
    c = fixed.lyapunov_curve((24, 25), samples=2, theta="0.25", v="12", transient=100, steps=2000)
    assert abs(c.lambda_[0, 0]) < 1e-3
    assert c.classes[c.class_[0, 0]] == "fixed" and c.period[0, 0] == 1


def test_curve_of_the_sticking_release_contracts():
    c = bouncer.Model(model="constant", a="23", eps="0.25").lyapunov_curve(
        (23, 31.5), samples=3, theta="0.5", v="4", transient=100, steps=500)
    assert (c.lambda_ == -math.inf).all() and (c.max_lambda == -math.inf).all()
    assert all(c.classes[k] == "sticking" for k in c.class_.ravel()) and (c.period == 1).all()


def test_curve_undecided_rows():
    c = bouncer.Model(model="elastic", a="1e-300").lyapunov_curve(
        ("1e-300", "2e-300"), samples=2, theta="0.1", v="1e15", transient=10, steps=50)
    assert np.isnan(c.lambda_).all() and all(c.classes[k] == "undecided" for k in c.class_.ravel())
    assert np.isnan(c.mean_lambda).all()


def test_curve_default_start_and_spread():
    # the triangle's fastest upward wall speed is 4: the default start is (0.1, 6); the R2
    # spread lies in the trapping region 4(1 + 3 eps)/(1 - eps) = 20 at eps = 1/2
    c = bouncer.Model(model="constant", a="20", eps="0.5").lyapunov_curve((20, 21), samples=1, ics=6,
                                                                          transient=10, steps=100)
    assert c.starts[0] == ("0.1", "6")
    assert all(0 < float(t) < 1 and 4 < float(v) <= 20 for t, v in c.starts[1:])
    assert len(set(c.starts)) == 6


def test_curve_threads_do_not_change_it():
    m = bouncer.Model(model="constant", a="20", eps="0.5")
    one = m.lyapunov_curve((20, 25), samples=6, ics=2, transient=50, steps=300, threads=1)
    two = m.lyapunov_curve((20, 25), samples=6, ics=2, transient=50, steps=300, threads=2)
    assert bits_equal(one.lambda_, two.lambda_) and (one.class_ == two.class_).all()


def test_curve_bad_input_names_the_option(fixed):
    with pytest.raises(ValueError, match="^vary: "):
        fixed.lyapunov_curve((10, 20), vary="b")
    with pytest.raises(ValueError, match="^eps: is only used with --model constant"):  # as the CLI says
        bouncer.Model(model="veldep", a="24", c="1000").lyapunov_curve((0.1, 0.2), vary="eps")
    with pytest.raises(ValueError, match="^range: "):
        fixed.lyapunov_curve((0.5, 1.5), vary="eps")
    with pytest.raises(ValueError, match="^precision: "):
        bouncer.Model(model="constant", a="24", eps="0.5", precision="interval:64").lyapunov_curve((24, 25))
    with pytest.raises(ValueError, match="^steps: "):
        fixed.portrait(["0.3"] * 201, ["7"] * 201, steps=100000)


def test_methods_are_typed_and_documented():
    import inspect
    for method in ("portrait", "lyapunov_curve"):
        f = getattr(bouncer.Model, method)
        sig = inspect.signature(f)
        assert sig.return_annotation is not inspect.Signature.empty, method
        for name, p in sig.parameters.items():
            if name != "self":
                assert p.annotation is not inspect.Parameter.empty, (method, name)
                assert name in f.__doc__, (method, name)
    for cls in (bouncer.Portrait, bouncer.ExponentCurve):
        assert cls.__annotations__ and cls.__doc__ and cls.__name__ in bouncer.__all__
