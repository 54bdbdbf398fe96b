"""The CLI-parity layer: each function runs the bouncer command of the same name in this
process (``bouncer._core.run``), with the same options, defaults, validation and code as the
command line, and turns its JSON and CSV into a Result. See the package's docstring."""

import csv as _csv
import json as _json
import shlex as _shlex
from decimal import Decimal as _Decimal
from numbers import Integral as _Integral, Real as _Real

import numpy as _np

from . import _core

# The class labels of the grid commands, in a fixed order: their int8 codes.
CLASSES = (
    "fixed", "periodic", "sticking", "quasiperiodic", "chaotic", "unbounded", "effective_sticking",
    "undecided", "transient_chaos", "outside", "no_sticking", "not_trapped", "never_sticks", "not_certified",
)

# Columns whose values are real numbers (of the run's precision: float64 in double).
_REAL = {"theta", "v", "tau", "stuck_theta", "stuck_v", "lambda", "lambda_error", "a", "eps", "c", "param",
         "value", "theta0", "v0", "stderr", "fraction", "regular", "v_max"}
_DOUBLE_PRECISIONS = ("double", "interval:double")


class Result(dict):
    """A command's answer: the CLI's JSON fields (``provenance`` among them) as keys, numpy
    arrays for its tables. Keys are also attributes where they do not clash with dict's own
    (``r.provenance``, ``r.theta``); ``r["items"]`` always works."""

    def __getattr__(self, key):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None

    def __dir__(self):
        return list(super().__dir__()) + [k for k in self if isinstance(k, str) and k.isidentifier()]

    def __repr__(self):
        head = "bouncer.Result"
        if "command_line" in self:
            head += " of `" + self["command_line"] + "`"
        lines = [head]
        for k, v in self.items():
            if k == "command_line":
                continue
            if k == "provenance":
                text = "{" + ", ".join(sorted(v)) + "}"
            elif isinstance(v, _np.ndarray):
                text = f"{v.dtype} array {v.shape}"
            elif isinstance(v, dict) and k == "table":
                text = "{" + ", ".join(v) + "} (arrays)"
            else:
                text = repr(v)
            lines.append(f"  {k}: {text if len(text) <= 100 else text[:90] + ' ...'}")
        return "\n".join(lines)


# ---- command lines -------------------------------------------------------------------------

def _decimal(value, name):
    """The text of one option value: strings as given, integers in full, floats as the exact
    decimal of their binary value (so the CLI sees exactly the double the caller holds)."""
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        raise TypeError(f"{name}: a flag; pass {name}=True alone, not inside a value")
    if isinstance(value, _Integral):
        return str(int(value))
    if isinstance(value, _Decimal):
        return str(value)
    if isinstance(value, _Real):
        x = float(value)
        if x != x or x in (float("inf"), float("-inf")):
            return repr(x)  # the CLI rejects it with its own message
        return str(_Decimal(x))
    raise TypeError(f"{name}: expected a decimal string or a number, got {type(value).__name__}")


_JOIN = {"grid": "x", "size": "x"}


def _option_text(name, value):
    if isinstance(value, (tuple, list, _np.ndarray)):
        sep = ":" if name.endswith("_range") or name == "range" else _JOIN.get(name, ",")
        return sep.join(_decimal(v, name) for v in value)
    return _decimal(value, name)


def _words(command, options):
    words = ["bouncer", command]
    for name, value in options.items():
        if value is None or value is False:
            continue
        flag = "--" + name.replace("_", "-")
        if value is True:
            words.append(flag)
        else:
            words += [flag, _option_text(name, value)]
    return words


def _python_name(option):
    return option.lstrip("-").replace("-", "_")


# These re-execute the bouncer executable (/proc/self/exe) for each item: in a Python process
# that would be the interpreter. They are shell commands.
_SUBPROCESS_COMMANDS = ("audit", "reproduce")


def run(command, **options):
    """Runs ``bouncer COMMAND --option value ...`` in this process and returns what it printed
    (text). The typed functions below are built on it; use it for what they do not cover
    (portrait, trajectory, tongues, merge). ``audit`` and ``reproduce`` rerun the executable
    and are refused: run them from a shell."""
    if command in _SUBPROCESS_COMMANDS:
        raise ValueError(f"{command}: runs the bouncer executable once per item; run it from a shell "
                         f"(bouncer {command} --help), not from Python")
    out, _ = _run_words(_words(command, options))
    return out


def _run_words(words):
    r = _core.run(words)
    kind = r["kind"]
    if kind in ("ok", "help"):
        return r["out"].decode("utf-8", "replace"), r["csv"].decode("utf-8", "replace")
    message = r["message"]
    if kind == "input":
        if r["unknown_option"]:
            unknown = _python_name(r["unknown_option"])
            hint = ""
            if "did you mean --" in message:
                hint = " (did you mean " + _python_name(message.split("did you mean ")[1].split("?")[0]) + "?)"
            raise TypeError(f"{words[1]}() got an unexpected keyword argument '{unknown}'{hint}")
        raise ValueError(message)
    if kind == "cancelled":
        raise KeyboardInterrupt
    raise RuntimeError(message)


def _model(options):
    """The CLI requires --model; here it follows from eps (constant) or c (veldep) when not
    given. Elastic has neither: model="elastic"."""
    if options.get("model") is None and options.get("scene") is None:
        if options.get("eps") is not None:
            options["model"] = "constant"
        elif options.get("c") is not None:
            options["model"] = "veldep"
    return options


def _json_result(command, options):
    words = _words(command, options)
    out, csv_text = _run_words(words)
    result = Result(_json.loads(out))
    result["command_line"] = _shlex.join(words)
    return result, csv_text


# ---- tables ---------------------------------------------------------------------------------

def _column(name, values, doubles):
    """Real columns: float64 when the values are doubles, else str. Other columns: int64 when
    every entry is an integer or empty (-1), else str."""
    base = name[:-3] if name.endswith(("_lo", "_hi")) else name
    if base in _REAL:
        if doubles:
            return _np.array([float(x) if x != "" else _np.nan for x in values], dtype=_np.float64)
        return _np.array(values, dtype=str)
    try:
        return _np.array([int(x) if x != "" else -1 for x in values], dtype=_np.int64)
    except ValueError:
        return _np.array(values, dtype=str)


def _table(columns, rows, doubles, coordinates=()):
    """dict column -> 1-D array. `coordinates` are always doubles (grid cell centres)."""
    data = {}
    for i, name in enumerate(columns):
        values = [row[i] for row in rows]
        data[name] = _column(name, values, doubles or name in coordinates)
    return data


def _csv_rows(text):
    lines = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    reader = _csv.reader(lines)
    header = next(reader)
    return header, list(reader)


def _codes(labels):
    table = list(CLASSES)
    for x in labels:
        if x not in table:
            table.append(x)
    index = {name: i for i, name in enumerate(table)}
    return _np.array([index[x] for x in labels], dtype=_np.int8), table


def _doubles(precision):
    return precision is None or precision in _DOUBLE_PRECISIONS


def _pair_intervals(data):
    """theta_lo, theta_hi -> theta as an (N, 2) array of [lo, hi]."""
    for name in [k[:-3] for k in list(data) if k.endswith("_lo")]:
        if name + "_hi" in data and name not in data:
            data[name] = _np.stack([data[name + "_lo"], data[name + "_hi"]], axis=1)


# ---- single orbits ----------------------------------------------------------------------------

def orbit(*, model=None, a=None, eps=None, c=None, theta="0.5", v="4", steps=None, precision="double", **options):
    """The orbit from (theta, v) (default: the release state (1/2, 4) of the triangle wall),
    ``steps`` steps (default 10, as the CLI).

    Returns a Result with the CLI's JSON fields (``provenance``, ``columns``, ``end``) and one
    array per column: ``n``, ``theta``, ``v``, ``event``, ``tau``, ... In double (and
    interval:double) the numbers are float64, bit for bit the CLI's; in other precisions
    they are decimal strings (``to_mpmath``). Interval runs have ``theta_lo``/``theta_hi``
    columns and ``theta`` as an (N, 2) array of [lo, hi]. ``end`` says how the run ended
    (completed, or stopped at an undecided step)."""
    options = _model(dict(model=model, a=a, eps=eps, c=c, theta=theta, v=v, steps=steps, precision=precision,
                          **options))
    options["format"] = "json"
    result, _ = _json_result("orbit", options)
    orbits = result.pop("orbits")
    rows = [row for o in orbits for row in o["rows"]]
    result["end"] = orbits[0]["end"] if len(orbits) == 1 else [o["end"] for o in orbits]
    result.update(_table(result["columns"], rows, _doubles(precision)))
    _pair_intervals(result)
    return result


def step(*, model=None, a=None, eps=None, c=None, theta="0.5", v="4", precision="double", **options):
    """One step of the impact map from (theta, v): a Result whose fields are the CLI's orbit
    row for step 1 as scalars (``theta``, ``v``, ``event``, ``tau``, ...) and ``provenance``."""
    r = orbit(model=model, a=a, eps=eps, c=c, theta=theta, v=v, steps=1, precision=precision, **options)
    if len(r["n"]) < 2:
        raise RuntimeError("the step was not decided: " + str(r["end"]))
    out = Result(provenance=r["provenance"], end=r["end"], command_line=r["command_line"])
    for name in r["columns"]:
        out[name] = r[name][1].item() if hasattr(r[name][1], "item") else r[name][1]
    for name in [k for k in r if k not in out and isinstance(r[k], _np.ndarray) and r[k].ndim == 2]:
        out[name] = tuple(x.item() for x in r[name][1])
    return out


def certify_sticking(*, model=None, a=None, eps=None, c=None, theta="0.5", v="4", **options):
    """Certified answer for the orbit from the exact decimals (theta, v): sticks at step k,
    never sticks (with the trapping set), or "not certified at N bits". The CLI's JSON as a
    Result (``certified``, ``outcome``, ``provenance``, ...)."""
    options = _model(dict(model=model, a=a, eps=eps, c=c, theta=theta, v=v, json=True, **options))
    return _json_result("certify-sticking", options)[0]


def sweep(*, model=None, a=None, eps=None, c=None, theta="0.5", v="4", steps=None, **options):
    """The precision sweep: where each precision's orbit leaves the certified enclosure
    (``steps`` default 1000, as the CLI).
    ``rows`` (one per precision) also come as arrays: ``precision``, ``bits``,
    ``leaves_enclosure_at`` (-1: never), ``sticking_period`` (-1: none)."""
    options = _model(dict(model=model, a=a, eps=eps, c=c, theta=theta, v=v, steps=steps, json=True, **options))
    result, _ = _json_result("sweep", options)
    rows = result.get("rows", [])
    result["precision"] = _np.array([r["precision"] for r in rows], dtype=str)
    for key in ("bits", "leaves_enclosure_at", "sticking_period"):
        result[key] = _np.array([-1 if r.get(key) is None else int(r[key]) for r in rows], dtype=_np.int64)
    return result


def periodic(*, model=None, a=None, eps=None, c=None, period=1, **options):
    """Newton's method for a period-q orbit (``guess=(theta, v)``, or ``grid=`` of starts)."""
    options = _model(dict(model=model, a=a, eps=eps, c=c, period=period, json=True, **options))
    return _json_result("periodic", options)[0]


def certify_periodic(*, model=None, a=None, eps=None, c=None, period=1, **options):
    """A certified periodic orbit (interval Newton/Krawczyk), at a parameter point or over a
    parameter interval (``a_range=``, ``eps_range=``, ``c_range=``)."""
    options = _model(dict(model=model, a=a, eps=eps, c=c, period=period, json=True, **options))
    return _json_result("certify-periodic", options)[0]


def continue_branch(*, model=None, a=None, eps=None, c=None, period=1, guess=None, vary="a", range=None,
                    **options):
    """Continues a period-q orbit in ``vary`` over ``range=(lo, hi)`` (CLI: ``bouncer
    continue``) and locates where its branch ends; ``certify=True`` certifies it."""
    options = _model(dict(model=model, a=a, eps=eps, c=c, period=period, guess=guess, vary=vary, range=range,
                          json=True, quiet=True, **options))
    return _json_result("continue", options)[0]


def lyapunov(*, model=None, a=None, eps=None, c=None, theta=None, v=None, **options):
    """The leading Lyapunov exponent of one orbit from (theta, v) (default: the release state
    (0.5, 4)), or with ``vary=`` and ``range=`` the curve lambda(parameter): then ``table``
    holds the CLI's CSV columns as arrays, and the curve starts where the CLI's does unless
    theta and v are given (theta = 0.1, v = the wall's fastest upward velocity + 2, then an
    R2 spread with ``ics=``)."""
    if options.get("vary") is None:
        theta = "0.5" if theta is None else theta
        v = "4" if v is None else v
    options = _model(dict(model=model, a=a, eps=eps, c=c, theta=theta, v=v, json=True, **options))
    if options.get("vary") is not None:
        options["quiet"] = True
        result, csv_text = _json_result("lyapunov", options)
        header, rows = _csv_rows(csv_text)
        result["table"] = _table(header, rows, _doubles(options.get("precision")), coordinates=("value",))
        return result
    return _json_result("lyapunov", options)[0]


def classify(*, model=None, a=None, eps=None, c=None, theta="0.5", v="4", **options):
    """The class of one orbit (fixed, periodic, sticking, chaotic, ...) with its evidence."""
    options = _model(dict(model=model, a=a, eps=eps, c=c, theta=theta, v=v, json=True, **options))
    return _json_result("classify", options)[0]


# ---- grids ----------------------------------------------------------------------------------

def _grid_run(command, options):
    options["json"] = True
    options["quiet"] = True
    result, csv_text = _json_result(command, options)
    header, rows = _csv_rows(csv_text)
    return result, header, rows


def _as_grid(result, header, rows, x, y, doubles):
    """Rows in CSV order (x fastest) -> result[x] (nx,), result[y] (ny,), and every other
    column as a 2-D (ny, nx) array; class columns as int8 codes (result["classes"])."""
    table = _table(header, rows, doubles, coordinates=(x, y))
    nx = len(dict.fromkeys(table[x].tolist()))
    ny = len(rows) // nx if nx else 0
    result[x] = table[x][:nx]
    result[y] = table[y][::nx]
    labels = []
    for name in header:
        if name in (x, y):
            continue
        col = table[name]
        if name in ("class", "double_class"):
            labels.append(name)
            continue
        result[name] = col.reshape(ny, nx)
    if labels:
        # one code table for every class column (class and, certified, double_class)
        codes, table_of_codes = _codes([lab for name in labels for lab in table[name].tolist()])
        for k, name in enumerate(labels):
            result[name] = codes[k * len(rows):(k + 1) * len(rows)].reshape(ny, nx)
        result["classes"] = table_of_codes
    result["table"] = table
    return result


def basin(*, model=None, a=None, eps=None, c=None, grid=(100, 100), **options):
    """Basins of attraction on a grid of starts (``theta_range=``, ``v_range=``; ``certify=True``
    certifies every point). Returns ``theta`` (N,), ``v`` (M,), ``class`` (M, N) int8 codes into
    ``classes``, ``period`` (M, N), the other CSV columns as (M, N) arrays, ``summary`` and
    ``provenance`` as in the CLI's JSON, and ``table`` (the CSV's columns)."""
    options = _model(dict(model=model, a=a, eps=eps, c=c, grid=grid, **options))
    result, header, rows = _grid_run("basin", options)
    return _as_grid(result, header, rows, "theta", "v", True)


def scan(*, model=None, a_range=None, eps_range=None, c_range=None, grid=(20, 20), **options):
    """Parameter scan: the share of each class among the starts of every parameter point.
    Returns ``a`` (P,), ``eps`` or ``c`` (Q,), one (Q, P) array per CSV column (counts of
    each class, ``total``; with ``certify=True`` the certified class codes), and ``summary``."""
    if model is None and options.get("scene") is None:
        model = "veldep" if c_range is not None else "constant"
    options = dict(model=model, a_range=a_range, eps_range=eps_range, c_range=c_range, grid=grid, **options)
    result, header, rows = _grid_run("scan", options)
    y = "c" if "c" in header and "eps" not in header else "eps"
    return _as_grid(result, header, rows, "a", y, True)


def bifurcation(*, model=None, a=None, eps=None, c=None, vary="a", range=None, samples=400, **options):
    """Bifurcation diagram: the recorded orbit points for each parameter value. Returns the
    point cloud as 1-D arrays named after the CSV's columns (the parameter, ``n``, ``theta``,
    ``v``, ...), ``table`` (the same), ``summary`` and ``provenance``."""
    options = _model(dict(model=model, a=a, eps=eps, c=c, vary=vary, range=range, samples=samples, **options))
    result, header, rows = _grid_run("bifurcation", options)
    table = _table(header, rows, _doubles(options.get("precision")), coordinates=(vary,))
    result.update(table)
    result["table"] = table
    return result


# ---- high precision ---------------------------------------------------------------------------

def to_mpmath(values, bits=None):
    """Decimal strings (or floats) of a result -> mpmath numbers at `bits` bits (default: the
    larger of 53 and mpmath's working precision). An (N, 2) array of [lo, hi] gives mpmath
    intervals (mpi) rounded outward, so they contain the printed enclosure."""
    import mpmath
    from mpmath import libmp

    prec = bits or max(53, mpmath.mp.prec)
    arr = _np.asarray(values)

    def parse(s, rounding):
        return mpmath.mpf(libmp.from_str(str(s), prec, rounding))

    if arr.ndim == 2 and arr.shape[1] == 2:
        return [mpmath.mpi(parse(lo, libmp.round_floor), parse(hi, libmp.round_ceiling)) for lo, hi in arr]
    if arr.ndim == 0:
        return parse(arr.item(), libmp.round_nearest)
    return [parse(s, libmp.round_nearest) for s in arr.tolist()]
