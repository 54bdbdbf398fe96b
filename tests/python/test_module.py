"""The Python module against the bouncer executable and against independent truth.

Run by ctest (python.pytest) with PYTHONPATH=build/python and BOUNCER_CLI=the executable.
Every function of the module has at least one test here that fails if its answer, its
types or its errors drift from the command line's.
"""

import json
import os
import pathlib
import re
import signal
import subprocess
import threading
import time
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest

import bouncer

CLI = os.environ.get("BOUNCER_CLI", str(pathlib.Path(__file__).resolve().parents[2] / "build/tools/bouncer"))
CONSTANT = dict(model="constant", a="24", eps="0.5")


def cli(*args, check=True):
    """Runs the executable; returns (status, stdout, stderr)."""
    p = subprocess.run([CLI, *args], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"bouncer {' '.join(args)} failed ({p.returncode}): {p.stderr}")
    return p.returncode, p.stdout, p.stderr


def words(command, **options):
    """The CLI's argument list for the same options as a module call."""
    return bouncer._words(command, options)[1:]


def stable(doc):
    """A JSON document without what legitimately differs between two runs: timings
    ("seconds", as audit skips them), the invocation (program path), and the hash of
    uncommitted changes in a developer's build."""
    if isinstance(doc, dict):
        out = {k: stable(v) for k, v in doc.items() if k not in ("seconds", "invocation")}
        if isinstance(out.get("commit"), str):  # a build from a changed tree: +dirty-HASH of when each was built
            out["commit"] = out["commit"].split("+dirty")[0]
        return out
    if isinstance(doc, list):
        return [stable(x) for x in doc]
    return doc


def module_json(result):
    """The part of a Result that came from the CLI's JSON (arrays and helpers removed)."""
    return stable({k: v for k, v in result.items() if not isinstance(v, np.ndarray)
                   and k not in ("command_line", "table", "classes", "end", "columns")})


def csv_rows(text):
    lines = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    return [ln.split(",") for ln in lines]


# ---- orbit and step -------------------------------------------------------------------------

@pytest.mark.parametrize("precision", ["double", "mpfr:256"])
def test_orbit_matches_cli_csv_bit_for_bit(precision):
    opts = dict(model="constant", a="28.82", eps="0.96", theta="0.3", v="7.5", steps=300, precision=precision)
    r = bouncer.orbit(**opts)
    _, out, _ = cli(*words("orbit", **opts), "--format", "csv")
    rows = csv_rows(out)
    header, body = rows[0], rows[1:]
    assert r["columns"] == header
    assert len(r["n"]) == len(body) == 301
    for j, name in enumerate(header):
        col = [row[j] for row in body]
        real = name in ("theta", "v", "tau", "stuck_theta", "stuck_v")
        if precision == "double" and real:
            expect = np.array([float(x) if x else np.nan for x in col])
            got = r[name]
            assert got.dtype == np.float64
            # bit for bit: same doubles, NaN where the CLI's field is empty
            assert np.array_equal(got, expect, equal_nan=True)
            assert np.array_equal(got.view(np.int64)[1:], expect.view(np.int64)[1:])
        elif real:
            assert r[name].dtype.kind == "U"
            assert r[name].tolist() == col
        elif r[name].dtype == np.int64:
            assert r[name].tolist() == [int(x) if x else -1 for x in col]
        else:
            assert r[name].tolist() == col


def test_orbit_dtypes_and_shapes():
    r = bouncer.orbit(**CONSTANT, theta="0.25", v="12", steps=50)
    assert r["theta"].shape == r["v"].shape == r["n"].shape == (51,)
    assert r["theta"].dtype == np.float64 and r["n"].dtype == np.int64 and r["event"].dtype.kind == "U"
    assert r["n"].tolist() == list(range(51))
    assert r["tau"][0] != r["tau"][0]  # the start row has no impact time: NaN
    assert r["end"]["status"] == "completed"
    assert r["provenance"]["precision"] == "double"


def test_interval_orbit_pairs_enclose_the_mpfr_orbit():
    lo_hi = bouncer.orbit(**CONSTANT, theta="0.25", v="12", steps=40, precision="interval:double")
    exact = bouncer.orbit(**CONSTANT, theta="0.25", v="12", steps=40, precision="mpfr:512")
    assert lo_hi["theta"].shape == (41, 2) and lo_hi["theta"].dtype == np.float64
    enclosures = bouncer.to_mpmath(lo_hi["v"], bits=53)
    points = bouncer.to_mpmath(exact["v"], bits=512)
    assert len(enclosures) == len(points) == 41
    for box, x in zip(enclosures, points):
        assert box.a <= x <= box.b


def test_step_is_the_first_orbit_step_and_agrees_with_512_bits():
    s = bouncer.step(**CONSTANT, theta="0.25", v="12")
    r = bouncer.orbit(**CONSTANT, theta="0.25", v="12", steps=1)
    assert (s["theta"], s["v"], s["event"]) == (r["theta"][1], r["v"][1], r["event"][1])
    assert isinstance(s["theta"], float) and isinstance(s["n"], int)
    # independent truth: the same step in MPFR at 512 bits agrees to double precision
    hi = bouncer.step(**CONSTANT, theta="0.25", v="12", precision="mpfr:512")
    assert isinstance(hi["v"], str)
    for name in ("theta", "v", "tau"):
        exact = Fraction(Decimal(hi[name]))
        assert abs(Fraction(s[name]) - exact) <= abs(exact) * Fraction(1, 2**50)


def test_float_arguments_are_exact_decimals():
    r = bouncer.orbit(model="constant", a=28.82, eps=0.96, theta=0.3, v=7.5, steps=5)
    assert r["provenance"]["inputs"]["a"] == str(Decimal(28.82))
    same = bouncer.orbit(model="constant", a="28.82", eps="0.96", theta="0.3", v="7.5", steps=5)
    # In double both are the nearest double of 28.82; in MPFR at 256 bits they differ.
    assert np.array_equal(r["v"], same["v"])
    hi_f = bouncer.orbit(model="constant", a=28.82, eps=0.96, theta=0.3, v=7.5, steps=5, precision="mpfr:256")
    hi_s = bouncer.orbit(model="constant", a="28.82", eps="0.96", theta="0.3", v="7.5", steps=5, precision="mpfr:256")
    assert hi_f["v"][5] != hi_s["v"][5]


def test_to_mpmath_recovers_the_printed_values_exactly():
    import mpmath
    r = bouncer.orbit(**CONSTANT, theta="0.25", v="12", steps=10, precision="mpfr:256")
    xs = bouncer.to_mpmath(r["v"], bits=256)
    with mpmath.workprec(256):
        for text, x in zip(r["v"].tolist(), xs):
            # bouncer prints enough digits to round-trip at 256 bits: mpmath agrees to them
            assert abs(x - mpmath.mpf(text)) <= abs(x) * mpmath.mpf(2) ** -255
    d = bouncer.orbit(**CONSTANT, theta="0.25", v="12", steps=10)
    assert [float(x) for x in bouncer.to_mpmath(d["v"], bits=53)] == d["v"].tolist()


# ---- certified answers agree with the CLI ---------------------------------------------------

def test_certify_sticking_as_in_the_issue_and_as_the_cli():
    r = bouncer.certify_sticking(eps="0.96", a="28.82")
    assert r["certified"] is True
    _, out, _ = cli(*words("certify-sticking", model="constant", a="28.82", eps="0.96", theta="0.5", v="4"), "--json")
    assert module_json(r) == stable(json.loads(out))


def test_certify_sticking_known_artefact_case():
    # eps = 0.5, a = 15 from the release state: double says "sticks"; the certified orbit does
    # not stick within the steps it covers (docs/claims.md).
    r = bouncer.certify_sticking(eps="0.5", a="15", max_steps=2000)
    assert r["outcome"] != "sticks"


def test_sweep_matches_cli():
    opts = dict(model="constant", a="15", eps="0.5", theta="0.5", v="4", steps=200)
    r = bouncer.sweep(**opts)
    _, out, _ = cli(*words("sweep", **opts), "--json")
    assert module_json(r) == stable(json.loads(out))
    assert r["precision"].dtype.kind == "U" and r["bits"].dtype == np.int64
    assert len(r["precision"]) == len(r["rows"]) and "double" in r["precision"].tolist()


def test_periodic_finds_the_eq5_fixed_point():
    # eq. 5: at a = 8(1+eps)/(p(1-eps)) = 24 (eps = 0.5, p = 1) the period-1 orbits form a
    # family: multipliers 1 (along the family) and eps^2 = 0.25 (hand-derived).
    r = bouncer.periodic(**CONSTANT, period=1, guess=("0.3", "12"))
    _, out, _ = cli(*words("periodic", **CONSTANT, period=1, guess=("0.3", "12")), "--json")
    assert module_json(r) == stable(json.loads(out))
    assert r["converged"] is True
    assert sorted(r["multiplier_moduli"]) == pytest.approx([0.25, 1.0], abs=1e-12)
    theta, v = r["points"][0]
    s = bouncer.step(**CONSTANT, theta=theta, v=v, precision="mpfr:256")
    assert float(s["theta"]) == pytest.approx(float(theta), abs=1e-12)
    assert float(s["v"]) == pytest.approx(float(v), abs=1e-12)


def test_certify_periodic_matches_cli():
    opts = dict(CONSTANT, period=1, guess=("0.3", "12"))
    r = bouncer.certify_periodic(**opts)
    _, out, _ = cli(*words("certify-periodic", **opts), "--json")
    assert module_json(r) == stable(json.loads(out))
    assert r["certified"] is True


def test_continue_branch_matches_cli():
    opts = dict(CONSTANT, period=1, guess=("0.3", "12"), vary="eps", range=("0.45", "0.55"))
    r = bouncer.continue_branch(**opts)
    _, out, _ = cli(*words("continue", **opts, json=True, quiet=True))
    assert module_json(r) == stable(json.loads(out))


def test_lyapunov_single_and_curve_match_cli():
    opts = dict(model="constant", a="28", eps="0.96", theta="0.5", v="4", steps=2000)
    r = bouncer.lyapunov(**opts)
    _, out, _ = cli(*words("lyapunov", **opts), "--json")
    assert module_json(r) == stable(json.loads(out))
    curve = dict(model="constant", eps="0.5", a="15", vary="a", range=("10", "20"), samples=5, steps=500,
                 transient=200)
    c = bouncer.lyapunov(**curve, threads=1)
    # the same curve from the same default start as the CLI's (0.1, 6), not (0.5, 4): issue 22
    _, out, _ = cli(*words("lyapunov", **curve), "--quiet")
    rows = csv_rows(out)
    assert c["table"]["value"].dtype == np.float64 and c["table"]["lambda"].dtype == np.float64
    assert c["table"]["value"].tolist() == [float(row[rows[0].index("value")]) for row in rows[1:]]
    assert c["table"]["class"].tolist() == [row[rows[0].index("class")] for row in rows[1:]]


def test_classify_known_sticking_orbit():
    # a = 20, eps = 0.3 from (0.3, 9) sticks with period 3 (the release state recurs).
    opts = dict(model="constant", a="20", eps="0.3", theta="0.3", v="9")
    r = bouncer.classify(**opts)
    assert r["class"] == "sticking" and r["period"] == 3
    _, out, _ = cli(*words("classify", **opts), "--json")
    assert module_json(r) == stable(json.loads(out))


# ---- grids ------------------------------------------------------------------------------------

def test_basin_arrays_match_cli_csv():
    opts = dict(model="constant", a="15", eps="0.5", grid=(6, 4), steps=200, transient=300)
    r = bouncer.basin(**opts, threads=2)
    _, out, _ = cli(*words("basin", **opts), "--quiet")
    rows = csv_rows(out)
    header, body = rows[0], rows[1:]
    assert r["theta"].shape == (6,) and r["v"].shape == (4,)
    assert r["class"].shape == (4, 6) and r["class"].dtype == np.int8
    assert r["period"].shape == (4, 6) and r["period"].dtype == np.int64
    labels = [r["classes"][code] for code in r["class"].ravel()]
    assert labels == [row[header.index("class")] for row in body]
    assert r["period"].ravel().tolist() == [int(row[header.index("period")]) for row in body]
    assert r["theta"].tolist() == [float(row[0]) for row in body[:6]]
    assert r["summary"]["points"] == 24


def test_certified_basin_agrees_with_the_cli_and_certify_sticking():
    opts = dict(model="constant", a="15", eps="0.5", grid=(3, 2), steps=300, certify=True)
    r = bouncer.basin(**opts)
    assert r["certified_steps"].shape == (2, 3) and r["double_class"].dtype == np.int8
    _, out, _ = cli(*words("basin", **opts), "--quiet")
    rows = csv_rows(out)
    assert [r["classes"][k] for k in r["class"].ravel()] == [row[2] for row in rows[1:]]
    # Each label against certify-sticking at that exact double start (sticking = sticks;
    # no_sticking = no sticking within the steps, or no further sticking after the first,
    # because the release orbit is free of sticking).
    release = bouncer.certify_sticking(model="constant", a="15", eps="0.5", max_steps=300)
    for j, v in enumerate(r["v"]):
        for i, theta in enumerate(r["theta"]):
            label = r["classes"][r["class"][j, i]]
            if label == "undecided":
                continue
            c = bouncer.certify_sticking(model="constant", a="15", eps="0.5", theta=float(theta), v=float(v),
                                         max_steps=300)
            assert c["certified"] is True
            if label == "sticking":
                assert c["outcome"] == "sticks"
            else:
                assert label == "no_sticking"
                assert c["outcome"] != "sticks" or release["outcome"] != "sticks"


def test_certified_veldep_basin_is_every_pixel_trapped():
    # docs/claims.md, row 18b: at a = 25, c = 1000 every start is certified trapped (period 3 or 31).
    r = bouncer.basin(model="veldep", a="25", c="1000", grid=(4, 3), transient=2000, steps=300, certify=True,
                      threads=2)
    labels = {r["classes"][k] for k in r["class"].ravel()}
    assert labels == {"periodic"} and set(r["period"].ravel().tolist()) <= {3, 31}
    assert r["summary"]["double_vs_certified"]["agrees"] == 12


def test_scan_shapes_and_cli():
    opts = dict(model="constant", a_range=("10", "20"), eps_range=("0.4", "0.6"), grid=(3, 2), ics=2, steps=50,
                transient=100)
    r = bouncer.scan(**opts)
    _, out, _ = cli(*words("scan", **opts), "--quiet")
    rows = csv_rows(out)
    assert r["a"].shape == (3,) and r["eps"].shape == (2,)
    assert r["total"].shape == (2, 3) and (r["total"] == 4).all()
    assert r["chaotic"].ravel().tolist() == [int(row[rows[0].index("chaotic")]) for row in rows[1:]]


def test_bifurcation_point_cloud_matches_cli():
    opts = dict(model="constant", eps="0.96", vary="a", range=("28", "30"), samples=3, transient=100, record=4,
                theta="0.5", v="4")
    r = bouncer.bifurcation(**opts)
    _, out, _ = cli(*words("bifurcation", **opts), "--quiet")
    rows = csv_rows(out)
    assert r["v"].dtype == np.float64 and r["v"].shape == (len(rows) - 1,)
    assert r["v"].tolist() == [float(row[rows[0].index("v")]) for row in rows[1:]]
    assert r["a"].tolist() == [float(row[0]) for row in rows[1:]]


# ---- bad input: the CLI's message, as ValueError -------------------------------------------------

IC = dict(theta="0.25", v="12")
BAD = [
    ("orbit", dict(model="constant", a="0", eps="0.5", **IC), r"^a: .*> 0"),
    ("orbit", dict(model="constant", a=-1, eps=0.5, **IC), r"^a: .*> 0"),
    ("orbit", dict(model="constant", a="1e10", eps="0.5", **IC), r"^a: .*<= 1e9"),
    ("orbit", dict(model="constant", a="24", eps="1.5", **IC), r"^eps: .*\[0, 1\]"),
    ("orbit", dict(model="constant", a="24", eps="1.0000000000000000000000001", **IC), r"^eps: .*\[0, 1\]"),
    ("orbit", dict(model="elastic", a="24", eps="0.5", **IC), r"^eps: .*constant"),
    ("orbit", dict(model="veldep", a="24", c="0", **IC), r"^c: .*> 0"),
    ("orbit", dict(model="constant", a=float("nan"), eps="0.5", **IC), r"^a: .*finite"),
    ("orbit", dict(model="constant", a="24", eps=float("inf"), **IC), r"^eps: .*finite"),
    ("orbit", dict(CONSTANT, theta="1", v="12"), r"^theta: .*\[0, 1\)"),
    ("orbit", dict(CONSTANT, theta="0.25", v="3.9"), r"^v: .*>= the wall velocity 4"),
    ("orbit", dict(CONSTANT, theta="0.25", v="1e16"), r"^v: .*<= 1e15"),
    ("orbit", dict(model="foo", a="24", **IC), r"^model: .*allowed: elastic, constant, veldep"),
    ("orbit", dict(CONSTANT, **IC, wall="asymmetric:1.5"), r"^wall: .*0 < R < 1"),
    ("orbit", dict(CONSTANT, **IC, precision="float"), r"^precision: .*16 <= BITS <= 1048576"),
    ("orbit", dict(CONSTANT, **IC, precision="mpfr:8"), r"^precision: .*16 <= BITS <= 1048576"),
    ("orbit", dict(CONSTANT, **IC, steps=-1), r"^steps: .*integer in \[0, "),
    ("orbit", dict(CONSTANT, **IC, steps="1.5"), r"^steps: .*integer in \[0, "),
    ("orbit", dict(model="constant", a="24", **IC), r"^eps: .*required"),
    ("orbit", dict(model="veldep", a="24", **IC), r"^c: .*required"),
    ("certify-sticking", dict(CONSTANT, **IC, max_bits="8"), r"^max-bits: "),
    ("certify-sticking", dict(CONSTANT, theta="0.25", v="2"), r"^v: .*wall velocity"),
    ("sweep", dict(CONSTANT, **IC, steps=0), r"^steps: "),
    ("periodic", dict(CONSTANT, period=0, guess=("0.3", "12")), r"^period: "),
    ("certify-periodic", dict(CONSTANT, period=1, guess=("0.3", "12"), max_bits="1"), r"^max-bits: "),
    ("classify", dict(CONSTANT, **IC, precision="interval:64"), r"^precision: "),
    ("lyapunov", dict(CONSTANT, **IC, steps=-5), r"^steps: "),
    ("basin", dict(CONSTANT, grid=(0, 3)), r"^grid: "),
    ("basin", dict(CONSTANT, grid=(3, 3), theta_range=("0.5", "2")), r"^theta-range: "),
    ("basin", dict(CONSTANT, grid=(3, 3), threads=0), r"^threads: "),
    ("scan", dict(model="constant", a_range=("10", "20"), eps_range=("0.4", "1.6"), grid=(2, 2)), r"^eps-range: "),
    ("bifurcation", dict(CONSTANT, vary="q", range=("1", "2"), **IC), r"^vary: "),
]

FUNCTIONS = {"orbit": bouncer.orbit, "certify-sticking": bouncer.certify_sticking, "sweep": bouncer.sweep,
             "periodic": bouncer.periodic, "certify-periodic": bouncer.certify_periodic,
             "classify": bouncer.classify, "lyapunov": bouncer.lyapunov, "basin": bouncer.basin,
             "scan": bouncer.scan, "bifurcation": bouncer.bifurcation}


@pytest.mark.parametrize("command,options,pattern", BAD, ids=[f"{c}:{p}" for c, _, p in BAD])
def test_bad_input_raises_the_cli_message(command, options, pattern, tmp_path):
    status, _, err = cli(*words(command, **options), check=False)
    assert status == 2, err
    assert err.startswith("bouncer: ") and err.count("\n") == 1
    message = err[len("bouncer: "):].rstrip("\n")
    assert re.search(pattern, message), message
    with pytest.raises(ValueError) as e:
        FUNCTIONS[command](**options)
    assert str(e.value) == message


def test_unknown_keyword_is_a_type_error_with_a_suggestion():
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'epss'.*did you mean eps"):
        bouncer.orbit(model="constant", a="24", epss="0.5")


def test_bad_input_to_a_grid_leaves_no_file(tmp_path):
    prefix = tmp_path / "basin"
    with pytest.raises(ValueError):
        bouncer.basin(**CONSTANT, grid=(3, 3), v_range=("1", "0"), out=str(prefix))
    assert list(tmp_path.iterdir()) == []


# ---- the GIL and interrupts -------------------------------------------------------------------

SLOW = dict(model="constant", a="15", eps="0.5", grid=(60, 60), steps=2000, transient=5000, threads=1)


def test_two_threads_compute_at_the_same_time():
    """Both calls must be inside the C++ computation at once: with the GIL held they would
    run one after the other and their intervals would not overlap."""
    spans = {}
    barrier = threading.Barrier(2)

    def work(k):
        barrier.wait()
        t0 = time.monotonic()
        bouncer.basin(**dict(SLOW, grid=(30, 30)))
        spans[k] = (t0, time.monotonic())

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    (a0, a1), (b0, b1) = spans[0], spans[1]
    assert a0 < b1 and b0 < a1  # the two computations overlapped in time
    # and Python ran meanwhile: a computation in a thread leaves the interpreter free
    ticks = 0
    worker = threading.Thread(target=bouncer.basin, kwargs=dict(SLOW, grid=(30, 30)))
    worker.start()
    while worker.is_alive():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    assert ticks > 20


def test_ctrl_c_interrupts_and_leaves_no_partial_file(tmp_path):
    prefix = tmp_path / "big"
    timer = threading.Timer(0.5, os.kill, args=(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        bouncer.basin(**dict(SLOW, grid=(400, 400)), out=str(prefix))
    assert time.monotonic() - t0 < 15  # the whole grid takes about a minute
    timer.cancel()
    left = [p.name for p in tmp_path.iterdir() if not p.name.endswith(".tiles")]
    assert left == []  # no CSV, PNG, JSON, nor any *.partial
    # the module works after an interrupt
    assert bouncer.step(**CONSTANT, theta="0.25", v="12")["event"] == "impact"


def test_ctrl_c_interrupts_a_single_certified_orbit():
    # 10^8 certified steps would take minutes; the interrupt lands within 256 steps.
    timer = threading.Timer(0.3, os.kill, args=(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        bouncer.certify_sticking(eps="0.96", a="28.82", max_steps=100000000)
    assert time.monotonic() - t0 < 15
    timer.cancel()
    assert bouncer.certify_sticking(eps="0.96", a="28.82", max_steps=1000)["certified"] is True


def test_result_carries_provenance_and_a_command_line_that_reruns_it():
    r = bouncer.classify(model="constant", a="20", eps="0.3", theta="0.3", v="9")
    assert r["provenance"]["command"] == "classify"
    assert r["command_line"].startswith("bouncer classify ")
    status, out, _ = cli(*r["command_line"].split()[1:])
    assert status == 0 and json.loads(out)["class"] == "sticking"


def test_example_makes_its_figure(tmp_path):
    pytest.importorskip("matplotlib")
    import struct
    import sys
    src = pathlib.Path(os.environ.get("BOUNCER_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
    png = tmp_path / "figure.png"
    p = subprocess.run([sys.executable, str(src / "examples/python/basin_and_sweep.py"), str(png)],
                       capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert p.returncode == 0, p.stderr
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = struct.unpack(">II", data[16:24])
    assert (width, height) == (1650, 660)
    assert len(data) > 20000  # two panels with content, not an empty canvas


def test_repr_names_the_command_and_the_fields():
    r = bouncer.classify(model="constant", a="20", eps="0.3", theta="0.3", v="9")
    text = repr(r)
    assert text.splitlines()[0].startswith("bouncer.Result of `bouncer classify --model constant")
    assert "  class: 'sticking'" in text and "  period: 3" in text


def test_run_covers_other_commands_and_refuses_the_subprocess_ones(tmp_path):
    assert bouncer.run("tongues", p_max=3, out=str(tmp_path / "t")) == ""  # the outputs are files
    assert (tmp_path / "t.png").stat().st_size > 1000
    # without out=, the CSV: eq. 5's curve a = 8(1+eps)/(p(1-eps)) starts at a = 8/p, eps = 0
    rows = csv_rows(bouncer.run("tongues", p_max=2, samples=16))
    assert rows[0][:3] == ["p", "a", "eps"] and rows[1][:3] == ["1", "8", "0"]
    assert json.loads((tmp_path / "t.json").read_text())["provenance"]["command"] == "tongues"
    for command in ("audit", "reproduce"):
        with pytest.raises(ValueError, match="run it from a shell"):
            bouncer.run(command)


# ---- hostile input and shared outputs (issue 21) -----------------------------------------------

def test_core_run_refuses_an_empty_command_line():
    r = bouncer._core.run([])
    assert r["status"] == 2 and "no command line" in r["message"]


def test_a_nul_byte_in_a_value_is_refused_not_cut():
    """C strings would end "24\\x00junk" at the NUL: the value must be refused, not taken as 24."""
    with pytest.raises(ValueError, match=r"^a: .*NUL byte"):
        bouncer.orbit(model="constant", a="24\x00junk", eps="0.5", theta="0.25", v="12", steps=2)


def test_two_threads_on_one_output_prefix_exclude_each_other(tmp_path):
    """One process, two commands writing one prefix: the second is refused at its start
    (open file description locks exclude threads of one process, as they exclude processes)."""
    prefix = str(tmp_path / "shared")
    started = threading.Event()
    errors, done = [], []

    def first():
        try:
            started.set()
            bouncer.basin(**dict(SLOW, grid=(80, 80)), out=prefix)
            done.append(1)
        except Exception as e:  # noqa: BLE001 - reported below
            errors.append(e)

    t = threading.Thread(target=first)
    t.start()
    started.wait()
    for _ in range(200):  # until the first one holds the prefix
        if pathlib.Path(prefix + ".csv.partial").exists():
            break
        time.sleep(0.01)
    with pytest.raises(ValueError, match=r"^out: .*in use by another command of this process"):
        bouncer.basin(**dict(SLOW, grid=(40, 40)), out=prefix)
    t.join()
    assert not errors and done == [1]
    assert pathlib.Path(prefix + ".csv").exists()


def test_keep_tiles_does_not_keep_the_lock(tmp_path):
    """After a command with keep_tiles=True returns, its prefix is free again: the same call
    runs (from the kept tiles), and so does a shell command on that prefix."""
    prefix = str(tmp_path / "kept")
    small = dict(CONSTANT, grid=(4, 3), transient=10, steps=16, threads=1)
    bouncer.basin(**small, out=prefix, keep_tiles=True)
    assert pathlib.Path(prefix + ".tiles").is_dir()
    bouncer.basin(**small, out=prefix, keep_tiles=True)
    status, _, err = cli(*words("basin", **small), "--out", prefix, "--quiet", check=False)
    assert status == 0, err
