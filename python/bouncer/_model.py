"""The library layer: ``Model``, the impact map with one set of parameters, built once, and
the analyses on it, each a call of the library's own function (python/module.cpp) that
returns a typed result. No science here: this file converts arguments to the CLI's option
texts and the native results into dataclasses."""

from __future__ import annotations

# (A private module: its names do not reach the bouncer namespace, which imports what it
# exports by name; they are plain here so that help() shows plain annotations.)
import dataclasses
from decimal import Decimal
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

from . import _core
from ._cli import CLASSES, _decimal

# The verdicts of basin(confirm=...) (analysis/classify.hpp PrecisionVerdict), "unchecked"
# for the starts outside the sample.
CONFIRM_VERDICTS = ("unchecked", "agrees", "artefact", "precision_dependent")

Interval = _core.Interval
Step = _core.Step
Orbit = _core.Orbit
Undecided = _core.Undecided

#: The codes of ``Orbit.event``: ``EVENTS[orbit.event[i]]`` is the name of row i's event.
EVENTS = ("start", "impact", "sticking", "ride")

#: A number given to bouncer: a decimal string or ``decimal.Decimal`` (exact), an int, or a
#: float (its exact binary value, e.g. 0.1 is 0.1000000000000000055511151231257827...).
Number = Union[str, int, float, Decimal]
#: A real number of a result: float in double, a decimal text (str) in long, dd, quad and
#: mpfr:BITS (``bouncer.to_mpmath`` converts it), an Interval in interval precisions.
Real = Union[float, str, Interval]


def _texts(**options: Any) -> Dict[str, List[str]]:
    """Keyword arguments -> the CLI's option texts ({"max-iter": ["30"]}); None is left out
    (the CLI's default applies), pairs become two texts."""
    out = {}
    for name, value in options.items():
        if value is None:
            continue
        key = name.replace("_", "-")
        if isinstance(value, (tuple, list)):
            out[key] = [_decimal(x, name) for x in value]
        else:
            out[key] = [_decimal(value, name)]
    return out


def _on_off(value: Any, name: str) -> Optional[str]:
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "on" if value else "off"
    raise TypeError(f"{name}: expected True, False, 'on' or 'off', got {type(value).__name__}")


def _range_text(value: Any, name: str) -> Optional[str]:
    if value is None or isinstance(value, str):
        return value
    lo, hi = value
    return _decimal(lo, name) + ":" + _decimal(hi, name)


def _build(cls, fields: Dict[str, Any]):
    return cls(**fields)


# ---- results ----------------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Classification:
    """What an orbit does in the long run (``bouncer classify``), with the evidence.

    class_: fixed | periodic | sticking | quasiperiodic | chaotic | unbounded |
        effective_sticking | undecided | transient_chaos
    period: q for fixed/periodic, the sticking period k for sticking, else 0
    lambda_: leading Lyapunov exponent per collision (NaN if not computed)
    evidence: one line: what decided the class
    growth_alpha, growth_per_step, phase_branches, accelerator_period, accelerator_gain,
    growth_kind: unbounded only (else None): v ~ n^alpha, mean dv per step, phase clusters,
        accelerator period Q and gain D per Q steps, accelerator | diffusive | irregular
    settled_class, settled_at: transient_chaos only (else None): what it settled on, from when
    transient, steps, max_period, recheck_factor: the classifier's window as used
    """
    class_: str
    period: int
    lambda_: float
    evidence: str
    growth_alpha: Optional[float]
    growth_per_step: Optional[float]
    phase_branches: Optional[int]
    accelerator_period: Optional[int]
    accelerator_gain: Optional[float]
    growth_kind: Optional[str]
    settled_class: Optional[str]
    settled_at: Optional[int]
    transient: int
    steps: int
    max_period: int
    recheck_factor: int


@dataclasses.dataclass(frozen=True)
class Lyapunov:
    """The leading Lyapunov exponent of one orbit (``bouncer lyapunov``).

    lambda_: per collision; -inf when contracted (a sticking step has Jacobian 0)
    stderr: standard error of the block means (NaN with fewer than 2 blocks)
    steps, transient, blocks: as measured
    contracted: a sticking or ride step in the window; unbounded: velocity grows without
        bound (growth_alpha: v ~ n^alpha); v_max: largest v in the window
    undecided: a step could not be completed; note: why, for the special outcomes
    """
    lambda_: float
    stderr: float
    steps: int
    transient: int
    blocks: int
    contracted: bool
    unbounded: bool
    growth_alpha: float
    v_max: float
    undecided: bool
    note: str


@dataclasses.dataclass(frozen=True)
class PeriodicOrbit:
    """A period-q orbit from damped Newton (``bouncer periodic``).

    converged; period: q asked for; minimal_period: the smallest d | q with P^d(x) = x
    points: the q points (theta, v) in orbit order
    multipliers: the eigenvalues of DP^q as (re, im), largest modulus first;
        multiplier_moduli: their moduli; complex_pair; marginal: a multiplier within 1e-6 of 1
        (all four None when Newton did not converge)
    stability: stable | unstable | marginal, or unknown when Newton did not converge
    events: what each step was (impact | sticking | ride); wall_periods: periods begun per step
        (empty when Newton did not converge)
    residual, tolerance, iterations; note: why not converged, or remarks
    """
    converged: bool
    period: int
    minimal_period: int
    points: List[Tuple[Real, Real]]
    multipliers: Optional[List[Tuple[Real, Real]]]
    multiplier_moduli: Optional[Tuple[float, float]]
    complex_pair: Optional[bool]
    marginal: Optional[bool]
    stability: str
    events: List[str]
    wall_periods: List[int]
    residual: float
    tolerance: float
    iterations: int
    note: str


@dataclasses.dataclass(frozen=True)
class BranchEnd:
    """Where a continued branch ends (one side).

    reason: range_end | border | fold | doubling | event_change | period_collapse | lost |
        max_points (doubling: the branch is born at the period doubling of the period-q/2
        orbit it closes onto, which detail names)
    param: a* (the bracket's midpoint); bracket: (lo, hi)
    margin: knot | clearance | speed | sticking for a border end, else None; impact: its step
        (1-based), knot: the wall knot involved (exact rational text), detail: one phrase
    last_point: the orbit's first point on the branch side
    beyond: what the map does just past a* (param, class_, period, lambda_, evidence,
        newton_orbit_events, newton_orbit_minimal_period, newton_orbit_relation: none |
        continuation | other_branch | mother | unrelated, as continue's JSON), or None; beyond_note
    accuracy: how far param can be trusted (docs/guide/dynamics.md, bouncer continue, "Printed digits"):
        kind estimate | given | not_estimated; for an estimate a_star_backed and
        a_star_plus_minus (the digits it backs), a_star_digits, bracket_estimate (lo, hi),
        error_estimate, refined_param, refined_bits; otherwise note. An estimate, not a proof.
    certified: with continue_branch(certify=True), the end's proof (a border end's two-sided
        enclosure of a*, a fold's, or a doubling end's: the period-q/2 orbit's period
        doubling), else None
    """
    reason: str
    param: Real
    bracket: Tuple[Real, Real]
    margin: Optional[str]
    impact: Optional[int]
    knot: Optional[str]
    detail: str
    last_point: Tuple[Real, Real]
    beyond: Optional[Dict[str, Any]]
    beyond_note: str
    accuracy: Dict[str, Any]
    certified: Optional[Dict[str, Any]] = None


@dataclasses.dataclass(frozen=True)
class Branch:
    """A period-q orbit continued in a parameter (``bouncer continue``), K points.

    vary: a | eps | c; period: q
    param: (K,) the parameter values, increasing; theta, v: (K, q) the orbit points
    multiplier_moduli: (K, 2); residual: (K,); min_margin: {knot, clearance, speed,
        sticking} -> (K,) the least margin of each kind over the orbit
    stability: stable | unstable | marginal per point; events: the event text per point
        ("I0 I1^ S0": impact, sticking, ride and segment; c = corner, ^ = indirect)
    start: index of the start point; low, high: the ends; bifurcations: period doubling,
        Neimark-Sacker and folds on the way (kind, param, bracket, accuracy); corrector_runs
    Arrays are float64 in double, str (decimal texts) in the other precisions.
    """
    vary: str
    period: int
    param: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    multiplier_moduli: np.ndarray
    residual: np.ndarray
    min_margin: Dict[str, np.ndarray]
    stability: List[str]
    events: List[str]
    start: int
    low: BranchEnd
    high: BranchEnd
    bifurcations: List[Dict[str, Any]]
    corrector_runs: int


@dataclasses.dataclass(frozen=True)
class StickingCertificate:
    """A certified answer about sticking for one exact start (``bouncer certify-sticking``).

    certified: the outcome's statement is proved (all but undecided)
    outcome: sticks | never_sticks | no_sticking_within_max_steps | undecided
    period: the sticking period (sticks only); statement: one line
    scalar, bits: the interval type and bits of the run that certified it
    steps_checked: steps certified free of sticking; reason: why undecided, or detail
    double_period: what plain double computes for the same question (None: no sticking)
    attractor: the trapping-set proof of never_sticks (period, iterate, entered_at, box)
    release_theta, release_v: the exact release state after the sticking (sticks), or None
    lohner_fallbacks, max_steps, schedule, attempts (one dict per run), seconds
    """
    certified: bool
    outcome: str
    period: Optional[int]
    scalar: Optional[str]
    bits: int
    steps_checked: int
    statement: str
    reason: str
    double_period: Optional[int]
    attractor: Optional[Dict[str, Any]]
    release_theta: Optional[str]
    release_v: Optional[str]
    lohner_fallbacks: int
    max_steps: int
    schedule: str
    attempts: List[Dict[str, Any]]
    seconds: float


@dataclasses.dataclass(frozen=True)
class ChaosProof:
    """A proof of chaos: a horseshoe of covering relations with a certified lower bound on the
    topological entropy (``bouncer certify-chaos``), replayed by a second interval library.

    certified: proved with MPFI and the certificate replayed valid in Arb
    statement: what is proved and what is not (a horseshoe is an invariant set, not
        necessarily the attractor), or why nothing was proved
    bound: h_top(F) >= bound per impact, an exact decimal text rounded down (None: not proved);
        bound_double: the same as a float rounded down; quotient: the exact rational q with
        bound = log(q)/k rounded down
    k: the coverings are of F^k; hsets: how many h-sets
    saddle: the saddle periodic orbit the horseshoe is built on (period, theta, v, lambda_u,
        lambda_s), or None
    replay_valid: the Arb replay's verdict (None: nothing to replay)
    certificate: the certificate as JSON text (save it; ``bouncer.check_certificate`` or
        ``bouncer check-certificate FILE`` replays it), or None
    seconds: the search and the coverings (not the replay)
    """
    certified: bool
    statement: str
    bound: Optional[str]
    bound_double: Optional[float]
    quotient: Optional[str]
    k: int
    hsets: int
    saddle: Optional[Dict[str, Any]]
    replay_valid: Optional[bool]
    certificate: Optional[str]
    seconds: float


@dataclasses.dataclass(frozen=True)
class CertificateCheck:
    """The replay of a chaos certificate in Arb (``bouncer check-certificate``).

    valid: every check held: the certificate proves its stated bound
    disjoint: the h-sets are pairwise disjoint (exact)
    coverings: (proved, message) per covering of the certificate, in its order
    bound: the certificate's stated bound; recomputed_bound: log(q)/k as an Arb ball (text)
    problems: every failed check, or ["valid"]; bits: Arb's precision
    """
    valid: bool
    disjoint: bool
    coverings: List[Tuple[bool, str]]
    bound: str
    recomputed_bound: str
    problems: List[str]
    bits: int


def check_certificate(certificate: str, bits: int = 256) -> CertificateCheck:
    """Replays a chaos certificate (its JSON text, as ``Model.certify_chaos`` returns it or
    ``bouncer certify-chaos --out`` writes it) with Arb, an interval library independent of the
    one that made it, and its own implementation of the map. A malformed certificate raises
    ValueError naming the field; a false one gives valid False and its problems.

    bits: Arb's precision, an integer in [32, 65536] (default 256)
    """
    return _build(CertificateCheck, _core._check_certificate(certificate, bits))


@dataclasses.dataclass(frozen=True)
class PeriodicCertificate:
    """A period-Q orbit proved by the Krawczyk operator (``bouncer certify-periodic``).

    certified; outcome: isolated | family | through_release | not_found | undecided
    statement: the theorem, one paragraph; reason: why not certified
    bits: the precision that certified; period; minimal_period (None unless certified)
    stability: stable | unstable | neutral-stable | neutral-unstable | superstable | undecided
    points: enclosures (theta, v) of the Q points, as Intervals; events; wall_periods
    multipliers: {kind: real | complex | undecided, trace, det, and mu1, mu2 (real) or re, im,
        modulus (complex)} as Intervals
    krawczyk: {unknowns, box, image, free, free_range, inflations} or None
    family: {parameter_at_theta, given_parameter, strip_theta, strip_v, strip_parameter}
        for a certified family, else None
    double_newton: the double-precision Newton point (texts); double_distance: its distance
        to the certified box (0 inside)
    schedule, attempts, seconds
    """
    certified: bool
    outcome: str
    statement: str
    reason: str
    bits: int
    period: int
    minimal_period: Optional[int]
    stability: str
    points: List[Tuple[Interval, Interval]]
    events: List[str]
    wall_periods: List[int]
    multipliers: Dict[str, Any]
    krawczyk: Optional[Dict[str, Any]]
    family: Optional[Dict[str, Any]]
    double_newton: Optional[Tuple[str, str]]
    double_distance: Optional[float]
    schedule: str
    attempts: List[Dict[str, Any]]
    seconds: float


@dataclasses.dataclass(frozen=True)
class Basin:
    """Basins of attraction (``bouncer basin``; the library's ``basin`` / ``certified_basin``).

    theta (N,), v (M,): the grid's cell centres as float64 (the nearest doubles); theta_text,
        v_text: the same numbers as the run's precision prints them (exact in that type)
    class_ (M, N) int8: codes into ``classes``; period (M, N): the attractor's period
        (sticking: k), 0 for classes without one
    classes: the code table, bouncer.CLASSES (class_[j, i] names classes[class_[j, i]])
    v_range: the velocity window (texts; the default is the trapping region)
    certified: True for certify=True, which also fills certified_steps, double_class (codes
        into classes), double_period, agreement (codes: "agrees" | "differs" | "undecided" |
        "outside", in ``agreements``) and scalar (the tier that decided each start)
    confirm (M, N) int8, for confirm=...: codes into ``confirm_verdicts`` ("unchecked" outside
        the sample; "agrees"; "artefact": the start's class at the run's precision is not what
        mpfr:B and mpfr:2B both give; "precision_dependent": those two differ too);
        check_class (codes into classes) and check_period: the class at mpfr:B where checked;
        differs_in (M, N) str: what differs between the run's class and mpfr:B's ("class",
        "period", "accelerator period 33 vs 11", ...), "" where they agree or unchecked;
        confirm_bits: B
    """
    theta: np.ndarray
    v: np.ndarray
    theta_text: List[str]
    v_text: List[str]
    class_: np.ndarray
    period: np.ndarray
    classes: Tuple[str, ...]
    v_range: Tuple[str, str]
    certified: bool
    certified_steps: Optional[np.ndarray] = None
    double_class: Optional[np.ndarray] = None
    double_period: Optional[np.ndarray] = None
    agreement: Optional[np.ndarray] = None
    agreements: Tuple[str, ...] = ("agrees", "differs", "undecided", "outside")
    scalar: Optional[np.ndarray] = None
    confirm: Optional[np.ndarray] = None
    confirm_verdicts: Tuple[str, ...] = CONFIRM_VERDICTS
    check_class: Optional[np.ndarray] = None
    check_period: Optional[np.ndarray] = None
    differs_in: Optional[np.ndarray] = None
    confirm_bits: Optional[int] = None


@dataclasses.dataclass(frozen=True)
class Scan:
    """A parameter scan (``bouncer scan``; the library's ``scan`` / ``certified_scan``).

    a (P,), y_values (Q,): the parameter points as float64; a_text, y_text as the run's
        precision prints them (certified: the exact decimals of the double points); y: "eps" or "c"
    counts (Q, P, K) int64: how many of the k x k starts of each point are of each class,
        the classes in the order of ``count_classes`` (the CSV's columns); None when certified
    certified: certify=True gives, per parameter point (Q, P), class_ (codes into
        ``classes``), period, certified_steps, double_class, double_period, agreement
        (codes into ``agreements``) and scalar, as for Basin
    """
    a: np.ndarray
    y_values: np.ndarray
    a_text: List[str]
    y_text: List[str]
    y: str
    certified: bool
    counts: Optional[np.ndarray] = None
    count_classes: Tuple[str, ...] = ()
    class_: Optional[np.ndarray] = None
    period: Optional[np.ndarray] = None
    classes: Tuple[str, ...] = CLASSES
    certified_steps: Optional[np.ndarray] = None
    double_class: Optional[np.ndarray] = None
    double_period: Optional[np.ndarray] = None
    agreement: Optional[np.ndarray] = None
    agreements: Tuple[str, ...] = ("agrees", "differs", "undecided", "outside")
    scalar: Optional[np.ndarray] = None


@dataclasses.dataclass(frozen=True)
class Bifurcation:
    """A bifurcation diagram (``bouncer bifurcation``; the library's ``bifurcation``): one row
    per recorded point, in the CSV's order.

    vary: "a" | "eps" | "c"; value, n, theta, v (float64), column (int64: the value's index),
        sticking (bool): the rows; values: each parameter value as the run's precision prints
        it; theta_text, v_text: the rows' numbers so (None in double, where the floats are exact)
    undecided: (column, step, reason) of each column stopped by an undecided step
    certified: certify=True: one dict per column (value: the exact parameter, class_,
        period, certified_steps, scalar, double_class, double_period, agreement), else None
    """
    vary: str
    value: np.ndarray
    column: np.ndarray
    n: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    sticking: np.ndarray
    values: List[str]
    theta_text: Optional[List[str]]
    v_text: Optional[List[str]]
    undecided: List[Tuple[int, int, str]]
    certified: Optional[List[Dict[str, Any]]]


@dataclasses.dataclass(frozen=True)
class Portrait:
    """The orbits of a phase portrait (``bouncer portrait``; the library's ``portrait``): one
    row per point, in the CSV's order.

    orbit (int64: the start's index), n (int64: the step, 0 for the start, which is a row
        only without a transient), theta, v (float64), event (int8 codes into ``EVENTS``:
        "start", "impact", "sticking", "ride"): the rows
    theta_text, v_text: the rows' numbers as the run's precision prints them (None in
        double, where the floats are exact)
    starts: the (theta, v) starts as given (exact decimal texts)
    undecided: (orbit, step, reason) of each orbit stopped by a step the precision could
        not decide
    steps, transient: as used
    """
    orbit: np.ndarray
    n: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    event: np.ndarray
    theta_text: Optional[List[str]]
    v_text: Optional[List[str]]
    starts: List[Tuple[str, str]]
    undecided: List[Tuple[int, int, str]]
    steps: int
    transient: int


@dataclasses.dataclass(frozen=True)
class ExponentCurve:
    """The leading Lyapunov exponent against a parameter (``bouncer lyapunov --vary``; the
    library's ``exponent_curve``): K values x N starts.

    vary: "a" | "eps" | "c"; value (K,) float64: the values; values: the same as the run's
        precision prints them
    starts: the N starts (theta, v) as exact decimal texts, the same at every value
    lambda_ (K, N) float64: the exponent per collision (-inf: a sticking step contracted the
        window; NaN: a step was undecided), bit for bit ``Model.lyapunov`` at that value and
        start; stderr (K, N): its standard error
    class_ (K, N) int8: codes into ``classes`` (bouncer.CLASSES), the class of each orbit
        where its window ended; period (K, N) int64
    max_lambda (K,): the largest exponent over the starts (NaN skipped); mean_lambda (K,)
        their mean (NaN if one is NaN): the CLI's JSON values
    """
    vary: str
    value: np.ndarray
    values: List[str]
    starts: List[Tuple[str, str]]
    lambda_: np.ndarray
    stderr: np.ndarray
    class_: np.ndarray
    period: np.ndarray
    max_lambda: np.ndarray
    mean_lambda: np.ndarray
    classes: Tuple[str, ...] = CLASSES


@dataclasses.dataclass(frozen=True)
class Attractor:
    """One attractor found by ``Model.attractors`` (``bouncer attractors``; run/attractors.hpp).

    id: its index in Attractors.attractors (largest basin first), the value of its starts' label
    kind: periodic | family | sticking | chaotic | quasiperiodic | effective_sticking |
        accelerator | escape | undecided
    period: q (periodic, family), k (sticking), Q (accelerator), else 0
    theta, v: float64 arrays of its points (periodic: the orbit; sticking: from the release;
        family: one member; aperiodic: a sample); theta_text, v_text: as the run's precision prints them
    multipliers: complex multipliers of the Newton orbit (periodic, family), larger modulus
        first; multiplier_moduli; stable
    certificate: the Krawczyk proof's summary {certified, outcome, bits, minimal_period,
        stability, reason, multipliers: {kind, mu1, mu2 | re, im, modulus as Intervals}}, or None
    lambda_, lambda_stderr: exponent per collision of an aperiodic set (else None);
        accelerator_gain: mean velocity gain per Q steps (accelerator; else None)
    family: {members_found, theta_min, theta_max} of a family, else None
    starts: starts in its basin; fraction, fraction_stderr: their share of the starts in the
        phase space and its binomial standard error; cells; evidence: one line
    """
    id: int
    kind: str
    period: int
    theta: np.ndarray
    v: np.ndarray
    theta_text: List[str]
    v_text: List[str]
    multipliers: List[complex]
    multiplier_moduli: List[float]
    stable: bool
    certificate: Optional[Dict[str, Any]]
    lambda_: Optional[float]
    lambda_stderr: Optional[float]
    accelerator_gain: Optional[float]
    family: Optional[Dict[str, Any]]
    starts: int
    fraction: float
    fraction_stderr: float
    cells: int
    evidence: str


@dataclasses.dataclass(frozen=True)
class Attractors:
    """Every attractor at a parameter point (``bouncer attractors``; the library's
    ``find_attractors``).

    attractors: list of Attractor, largest basin first
    label: int32 per start: the attractor's id, UNDECIDED (-1: no decision in max_steps) or
        OUTSIDE (-2: below the wall's velocity); shape (M, N) for sampling "grid" (row j, column
        i: theta[j, i], v[j, i]), (N * M,) for "halton"
    theta, v: float64 per start, the same shape as label
    v_range: the starts' velocity window (texts; the default is the trapping region)
    inside, outside, undecided: starts; undecided_fraction, undecided_stderr
    steps: map steps taken; seconds, certify_seconds: wall times
    """
    UNDECIDED = -1
    OUTSIDE = -2
    attractors: List[Attractor]
    label: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    sampling: str
    v_range: Tuple[str, str]
    inside: int
    outside: int
    undecided: int
    undecided_fraction: float
    undecided_stderr: float
    steps: int
    seconds: float
    certify_seconds: float


def _grid_text(value: Any, name: str) -> Optional[str]:
    if value is None or isinstance(value, str):
        return value
    nx, ny = value
    return f"{int(nx)}x{int(ny)}"


def _recode(raw: np.ndarray, names: List[str], table: Tuple[str, ...], shape: Tuple[int, int]) -> np.ndarray:
    """Codes into the native call's own name list -> codes into `table`, reshaped."""
    remap = np.array([table.index(n) if n in table else -1 for n in names] or [0], dtype=np.int8)
    return remap[raw].reshape(shape)


def _confirm_text(confirm: Union[bool, int]) -> Optional[str]:
    """basin(confirm=...) as the CLI's --confirm[=BITS]: False -> absent, True -> 256 bits."""
    if confirm is False or confirm is None:
        return None
    if confirm is True:
        return "256"
    if isinstance(confirm, int):
        return str(confirm)
    raise TypeError(f"confirm: expected True, False or a number of bits, got {type(confirm).__name__}")


def _grid_fields(d: Dict[str, Any]) -> Dict[str, Any]:
    """The per-cell arrays of a native grid result, reshaped to (M, N), codes into CLASSES."""
    shape = tuple(d["shape"])
    names = d["class_names"]
    agreements = ("agrees", "differs", "undecided", "outside")
    out = {"class_": _recode(d["class_"], names, CLASSES, shape), "period": d["period"].reshape(shape)}
    if "agreement" in d:
        out.update(certified_steps=d["certified_steps"].reshape(shape),
                   double_class=_recode(d["double_class"], names, CLASSES, shape),
                   double_period=d["double_period"].reshape(shape),
                   agreement=_recode(d["agreement"], names, agreements, shape),
                   scalar=np.array(d["scalar"], dtype=str).reshape(shape))
    if "confirm" in d:
        out.update(confirm=_recode(d["confirm"], d["confirm_names"], CONFIRM_VERDICTS, shape),
                   check_class=_recode(d["check_class"], names, CLASSES, shape),
                   check_period=d["check_period"].reshape(shape),
                   differs_in=np.array(d["differs_in"], dtype=str).reshape(shape), confirm_bits=d["confirm_bits"])
    return out


# ---- the model ----------------------------------------------------------------------------------

class Model(_core.Model):
    """The piecewise linear bouncer with one set of parameters: its impact map, orbits and
    analyses, computed by the library (the same code as the command line; the parameters
    are validated once, here).

    Keyword arguments (the CLI's options, ``--downward-sticking`` is ``downward_sticking``):

    model: "constant" (restitution eps), "veldep" (eps(v) = exp(-|(v- - fdot)/c|^(3/5))) or
        "elastic". Default: constant when eps is given, veldep when c is given.
    a: dimensionless gravity a = g T^2 / A, a decimal with 0 < a <= 1e9 (required).
    eps: restitution coefficient, a decimal in [0, 1] (model constant only, required there).
    c: scale of eps(v), a decimal > 0 (model veldep only, required there).
    wall: "triangle" (default) | "sawtooth" | "asymmetric:R" (0 < R < 1) |
        "knots:0:H0,S1:H1,..." (a continuous periodic piecewise-linear wall).
    downward_sticking: "paper" (default) | "impact": a collapse on a downward wall at its
        upward turn rides on to the next release (paper) or is an impact there.
    veldep_collapse: False (default) | True (model veldep only): stick when the chatter
        provably collapses before the wall turns.
    precision: "double" (default) | "long" | "dd" | "quad" | "mpfr:BITS" | "interval:BITS" |
        "interval:double", 16 <= BITS <= 1048576. step and orbit run in it; the analyses
        (classify, lyapunov, periodic, continue_branch) need a point precision (not
        interval); the certified ones (certify_sticking, certify_periodic) choose their own
        interval precisions and ignore it.

    Numbers: decimal strings and ``decimal.Decimal`` are exact (``a="28.82"``); ints exact;
    a float is the exact decimal of its binary value (``a=28.82`` is 28.8200000000000002842...:
    the same double in double precision, another number at 256 bits).

    Errors: bad input raises ValueError with bouncer's one-line message, which names the
    option and its range (``ValueError: eps: must be in [0, 1] (got 1.5)``); an undecided
    interval step raises bouncer.Undecided; Ctrl-C raises KeyboardInterrupt (long calls run
    with the GIL released and check for it every 256 steps).

    Example::

        m = bouncer.Model(model="constant", a="24", eps="0.5")
        s = m.step(0.3, 9.5)            # bouncer.Step(theta=0.15033547982814893, v=11.454025757937787)
        s.event, s.tau                  # ('impact', 0.8503354798281488)
        theta, v = m.step(*s)           # a Step is the tuple (theta, v)
        o = m.orbit(0.3, 9.5, 1000)     # Orbit: o.theta, o.v, ... numpy arrays
    """

    def __init__(self, *, model: Optional[str] = None, a: Optional[Number] = None, eps: Optional[Number] = None,
                 c: Optional[Number] = None, wall: Optional[str] = None, downward_sticking: Optional[str] = None,
                 veldep_collapse: Union[bool, str, None] = None, precision: str = "double") -> None:
        if model is None:
            model = "constant" if eps is not None else "veldep" if c is not None else None
        super().__init__(_texts(model=model, a=a, eps=eps, c=c, wall=wall, downward_sticking=downward_sticking,
                                veldep_collapse=_on_off(veldep_collapse, "veldep_collapse"), precision=precision))

    def __repr__(self) -> str:
        given = ", ".join(f"{k.replace('-', '_')}={v!r}" for k, v in self.options.items())
        return f"bouncer.Model({given})"

    # step(theta, v) -> Step is the native method (module.cpp): no Python frame in between.
    # A Step is the tuple (theta, v) with the rest of the step as attributes.

    def orbit(self, theta: Number, v: Number, steps: Optional[int] = None, *, every: Optional[int] = None,
              method: Optional[str] = None) -> Orbit:
        """The orbit from (theta, v) as numpy arrays (``bouncer orbit``, without the text).

        theta: phase in [0, 1); v: velocity after the impact, at least the wall's velocity
            at theta, at most 1e15 (exact decimals, ints, or floats as their binary value)
        steps: number of steps, an integer in [0, 1e15] (default 10, as the CLI); the
            arrays have one row per kept step and the start row
        every: keep every K-th step (and the last), an integer in [1, 1e15] (default 1)
        method: interval precisions only: "lohner" (default, as the CLI: Lohner's QR
            method, tight enclosures) | "naive" (iterate the box)

        Returns an Orbit (see its fields); an undecided interval step ends the run with
        ``status == "undecided"`` and ``reason``. More than 1e8 rows is refused (raise every).
        """
        return self._orbit(_texts(theta=theta, v=v, steps=steps, every=every, method=method))

    def classify(self, theta: Number, v: Number, *, transient: Optional[int] = None, steps: Optional[int] = None,
                 max_period: Optional[int] = None, recheck_factor: Optional[int] = None) -> Classification:
        """The long-run class of the orbit from (theta, v) (``bouncer classify``).

        theta, v: the start, as for orbit
        transient: steps discarded first, an integer in [0, 1e10] (default 5000, the paper's)
        steps: steps examined, an integer in [8, 1e9] (default 500, the paper's)
        max_period: longest period looked for, an integer in [1, steps/2] (default
            min(64, steps/2))
        recheck_factor: a chaotic label is re-checked F x max(transient, steps) steps later
            (settled: transient_chaos), an integer in [0, 1000], 0 = off (default 20)
        """
        return _build(Classification, self._classify(_texts(
            theta=theta, v=v, transient=transient, steps=steps, max_period=max_period, recheck_factor=recheck_factor)))

    def lyapunov(self, theta: Number, v: Number, *, transient: Optional[int] = None, steps: Optional[int] = None,
                 blocks: Optional[int] = None) -> Lyapunov:
        """The leading Lyapunov exponent per collision of the orbit from (theta, v), through
        the AD tangent map (``bouncer lyapunov``; the exponent curves of ``--vary`` are
        ``lyapunov_curve``).

        theta, v: the start, as for orbit
        transient: steps discarded first, an integer in [0, 1e12] (default 1000)
        steps: steps measured, an integer in [1, 1e12] (default 10000)
        blocks: blocks of the error estimate, an integer in [1, 10000] (default 20)
        """
        return _build(Lyapunov, self._lyapunov(_texts(theta=theta, v=v, transient=transient, steps=steps,
                                                      blocks=blocks)))

    def periodic(self, period: int, *, guess: Optional[Tuple[Number, Number]] = None,
                 max_iter: Optional[int] = None, grid: Optional[int] = None) -> PeriodicOrbit:
        """A period-q orbit by damped Newton, with its multipliers (``bouncer periodic``).

        period: q, an integer in [1, 100]
        guess: (theta, v) to start Newton from (validated as a start); default: a grid of
            guesses in the trapping region
        max_iter: Newton iterations per guess, an integer in [1, 10000] (default 60)
        grid: guesses per axis without guess, an integer in [1, 64] (default 8)
        """
        return _build(PeriodicOrbit, self._periodic(_texts(period=period, guess=guess, max_iter=max_iter, grid=grid)))

    def continue_branch(self, period: int, guess: Tuple[Number, Number], range: Tuple[Number, Number], *,
                        vary: str = "a", step: Optional[Number] = None, max_points: Optional[int] = None,
                        max_iter: Optional[int] = None, beyond: Optional[Number] = None,
                        transient: Optional[int] = None, steps: Optional[int] = None,
                        max_period: Optional[int] = None, recheck_factor: Optional[int] = None,
                        certify: bool = False) -> Branch:
        """Continues the period-q orbit near ``guess`` in ``vary`` over ``range`` from the
        model's own value of that parameter, and locates where the branch ends
        (``bouncer continue``, without its pictures).

        period: q, an integer in [1, 2000]
        guess: (theta, v) near the orbit at the model's parameter value
        range: (lo, hi), decimals with lo < hi, both valid for the model, containing the
            model's value of the parameter
        vary: "a" (default) | "eps" (model constant) | "c" (model veldep)
        step: first continuation step, a decimal in (0, hi - lo] (default (hi - lo)/100)
        max_points: most branch points, both directions together, an integer in
            [2, 100000] (default 2000)
        max_iter: Newton iterations per corrector run, an integer in [1, 10000] (default 30)
        beyond: classify at a* + beyond * max(1, |a*|) past each end, a decimal in (0, 0.1]
            (default 1e-6)
        transient, steps, max_period, recheck_factor: the classifier past each end, as in
            classify (defaults 5000, 500, min(64, steps/2), 20)
        certify: True: the proofs of ``continue --certify``: each border end's a* enclosed on
            both sides (low/high ``certified``: kind "border", certified, bits, enclosure (an
            Interval), width, margin, margin_text, events, formulation ("composed": the
            first orbit point unknown; "shooting": all of them), bracket_contains, statement,
            reason, one_sided_certified, one_sided_bound), each period doubling and fold, on
            the branch (each bifurcation's "certified") or at a fold or doubling end (kind "smooth":
            certified, bits, enclosure, width, other_multiplier (an Interval), events,
            statement, reason); None where an end has no certifier
        """
        d = self._continue_branch(_texts(
            period=period, guess=guess, range=_range_text(range, "range"), vary=vary, step=step,
            max_points=max_points, max_iter=max_iter, beyond=beyond, transient=transient, steps=steps,
            max_period=max_period, recheck_factor=recheck_factor, certify="true" if certify else None))
        d["low"] = _build(BranchEnd, d["low"])
        d["high"] = _build(BranchEnd, d["high"])
        return _build(Branch, d)

    def certify_sticking(self, theta: Number = "0.5", v: Number = "4", *, max_steps: Optional[int] = None,
                         max_bits: Optional[int] = None, start_bits: Union[int, str, None] = None,
                         method: Optional[str] = None,
                         prove_attractor: Union[bool, str, None] = None) -> StickingCertificate:
        """A certified answer: does the orbit of the exact start (theta, v) stick, and when
        (``bouncer certify-sticking``; model constant). Interval arithmetic with precision
        escalation, whatever the model's precision.

        theta, v: the start (default: the release state (0.5, 4)), as for orbit
        max_steps: follow the orbit at most this many steps, an integer in [1, 1e9]
            (default 100000)
        max_bits: largest interval precision of the schedule, an integer in
            [16, 1048576] (default 4096)
        start_bits: "double" (default: interval:double first, then MPFI at 64, 128, ...)
            or BITS (MPFI at BITS, 2 BITS, ...), at most max_bits
        method: "lohner" (default) | "naive"
        prove_attractor: True (default) | False: when no sticking is found, try to prove
            that the orbit never sticks
        """
        return _build(StickingCertificate, self._certify_sticking(_texts(
            theta=theta, v=v, max_steps=max_steps, max_bits=max_bits, start_bits=start_bits, method=method,
            prove_attractor=_on_off(prove_attractor, "prove_attractor"))))

    def certify_periodic(self, period: int, *, guess: Optional[Tuple[Number, Number]] = None,
                         vary: Optional[str] = None, family: Optional[str] = None,
                         max_bits: Optional[int] = None, start_bits: Optional[int] = None,
                         max_iter: Optional[int] = None, grid: Optional[int] = None) -> PeriodicCertificate:
        """A period-Q orbit proved to exist (and be locally unique) by the Krawczyk operator,
        with enclosures of its points and multipliers (``bouncer certify-periodic`` at the
        model's parameter values; over a parameter range: ``bouncer.certify_periodic(...,
        a_range=...)``). Interval arithmetic with precision escalation.

        period: Q, an integer in [1, 2000]
        guess: (theta, v) for Newton (default: a grid of guesses in the trapping region)
        vary: the parameter of a family, its unknown: "a" (default) | "eps" | "c"
        family: "auto" (default: when Newton finds a multiplier 1) | "on" | "off"
        max_bits: largest precision of the schedule, an integer in [16, 1048576] (default 1024)
        start_bits: first precision (64, 128, ... doubling), an integer in [16, 1048576]
            at most max_bits (default 64)
        max_iter: Newton iterations, an integer in [1, 10000] (default 60)
        grid: Newton guesses per axis without guess, an integer in [1, 64] (default 8)
        """
        return _build(PeriodicCertificate, self._certify_periodic(_texts(
            period=period, guess=guess, vary=vary, family=family, max_bits=max_bits, start_bits=start_bits,
            max_iter=max_iter, grid=grid)))


    def certify_chaos(self, *, bits: Optional[int] = None, max_period: Optional[int] = None,
                      max_pieces: Optional[int] = None, replay_bits: Optional[int] = None) -> ChaosProof:
        """A proof that the map has positive topological entropy (``bouncer certify-chaos``):
        a saddle periodic orbit and a homoclinic orbit found from the model, h-sets along it,
        their covering relations proved with MPFI, and the certificate replayed in Arb.

        bits: MPFI precision of the coverings, an integer in [32, 4096] (default 128)
        max_period: saddles of period 1..Q are searched, an integer in [1, 8] (default 4)
        max_pieces: finest subdivision of an h-set per side, an integer in [1, 1024] (default 64)
        replay_bits: Arb's precision of the replay, an integer in [32, 65536] (default 256)
        """
        return _build(ChaosProof, self._certify_chaos(_texts(
            bits=bits, max_period=max_period, max_pieces=max_pieces, replay_bits=replay_bits)))

    def basin(self, *, grid: Tuple[int, int] = (100, 100), theta_range: Optional[Tuple[Number, Number]] = None,
              v_range: Optional[Tuple[Number, Number]] = None, transient: Optional[int] = None,
              steps: Optional[int] = None, max_period: Optional[int] = None, recheck_factor: Optional[int] = None,
              certify: bool = False, max_bits: Optional[int] = None, threads: Optional[int] = None,
              confirm: Union[bool, int] = False, confirm_sample: Union[int, str, None] = None) -> Basin:
        """Basins of attraction: every start of an N x M grid (cell centres) classified, or
        certified (``bouncer basin``, the same library call, reader and defaults).

        grid: (N, M) phases by velocities, each in [1, 8192] (default (100, 100))
        theta_range: (T0, T1) within [0, 1] (default (0, 1))
        v_range: (V0, V1) within +-1e15 (default: the trapping region; needed for the elastic
            model and eps = 1); starts below the wall's velocity are "outside"
        transient, steps, max_period, recheck_factor: the classifier's window, as classify
        certify: True: every start certified (constant, elastic, or veldep without collapse;
            the model's precision must be double, the twin run); max_bits: the schedule's last
            MPFI precision, an integer in [64, 4096] (default 256)
        threads: worker threads, an integer >= 1 (default: all cores); results do not depend on it
        confirm: True (mpfr:256) or a number of bits B in [64, 65536]: a sample of the starts
            classified again at mpfr:B and mpfr:2B, as single-point classify does, which flags
            where the run's class is a floating-point artefact (``basin --confirm``); not with
            certify. confirm_sample: how many starts, an integer >= 1 or "all" (default 1000;
            a lattice of the grid, independent of threads)
        """
        d = self._basin(_texts(grid=_grid_text(grid, "grid"), theta_range=_range_text(theta_range, "theta_range"),
                               v_range=_range_text(v_range, "v_range"), transient=transient, steps=steps,
                               max_period=max_period, recheck_factor=recheck_factor,
                               certify="true" if certify else None, max_bits=max_bits, threads=threads,
                               confirm=_confirm_text(confirm), confirm_sample=confirm_sample))
        return Basin(theta=d["theta"], v=d["v"], theta_text=d["theta_text"], v_text=d["v_text"], classes=CLASSES,
                     v_range=tuple(d["v_range"]), certified=d["certified"], **_grid_fields(d))

    def attractors(self, *, starts: Tuple[int, int] = (100, 100), sampling: Optional[str] = None,
                   theta_range: Optional[Tuple[Number, Number]] = None, v_range: Optional[Tuple[Number, Number]] = None,
                   cells: Optional[Tuple[int, int]] = None, recurrences: Optional[int] = None,
                   attractor_steps: Optional[int] = None, hits: Optional[int] = None, lost_steps: Optional[int] = None,
                   max_steps: Optional[int] = None, lyapunov_steps: Optional[int] = None,
                   transient: Optional[int] = None, steps: Optional[int] = None, max_period: Optional[int] = None,
                   recheck_factor: Optional[int] = None, certify: bool = True, max_bits: Optional[int] = None,
                   threads: Optional[int] = None) -> Attractors:
        """Every attractor at this parameter point, with its basin share (``bouncer attractors``
        without --vary: the same library call, reader, defaults and messages).

        starts: (N, M) phases by velocities, each in [1, 8192], N*M <= 4e6 (default (100, 100));
            sampling: "grid" (default, the cell centres, as basin) | "halton"
        theta_range, v_range: the starts' window (default theta in [0, 1], v the trapping region)
        cells: (N, M) of the recurrence grid, each in [16, 4096] (default (512, 512))
        recurrences, attractor_steps, hits, lost_steps, max_steps, lyapunov_steps: the mapper's
            options, as the CLI's; transient, steps, max_period, recheck_factor: the classifier's
        certify: prove periodic attractors and sticking cycles (Krawczyk), max_bits in [64, 4096]
        threads: worker threads (default: all cores); results do not depend on it
        """
        d = self._attractors(_texts(starts=_grid_text(starts, "starts"), sampling=sampling,
                                    theta_range=_range_text(theta_range, "theta_range"),
                                    v_range=_range_text(v_range, "v_range"), cells=_grid_text(cells, "cells"),
                                    recurrences=recurrences, attractor_steps=attractor_steps, hits=hits,
                                    lost_steps=lost_steps, max_steps=max_steps, lyapunov_steps=lyapunov_steps,
                                    transient=transient, steps=steps, max_period=max_period,
                                    recheck_factor=recheck_factor, no_certify=None if certify else "true",
                                    max_bits=max_bits, threads=threads))
        shape = tuple(d["shape"]) if d["shape"] is not None else (len(d["label"]),)
        found = [Attractor(**a) for a in d["attractors"]]
        return Attractors(attractors=found, label=d["label"].reshape(shape), theta=d["theta"].reshape(shape),
                          v=d["v"].reshape(shape), sampling=d["sampling"], v_range=tuple(d["v_range"]),
                          inside=d["inside"], outside=d["outside"], undecided=d["undecided"],
                          undecided_fraction=d["undecided_fraction"], undecided_stderr=d["undecided_stderr"],
                          steps=d["steps"], seconds=d["seconds"], certify_seconds=d["certify_seconds"])

    def scan(self, *, a_range: Tuple[Number, Number], eps_range: Optional[Tuple[Number, Number]] = None,
             c_range: Optional[Tuple[Number, Number]] = None, grid: Tuple[int, int] = (20, 20),
             ics: Optional[int] = None, theta_range: Optional[Tuple[Number, Number]] = None,
             v_range: Optional[Tuple[Number, Number]] = None, transient: Optional[int] = None,
             steps: Optional[int] = None, max_period: Optional[int] = None, recheck_factor: Optional[int] = None,
             recheck: Optional[str] = None, certify: bool = False, theta: Optional[Number] = None,
             v: Optional[Number] = None, max_bits: Optional[int] = None, threads: Optional[int] = None) -> Scan:
        """A parameter scan over (a, eps) (constant model) or (a, c) (veldep model) with this
        model's law, wall and sticking rule (its own a and eps or c are not used): at each of
        P x Q points, K x K starts classified and counted (``bouncer scan``).

        a_range; eps_range (constant) or c_range (veldep): the ranges (cell centres)
        grid: (P, Q), each in [1, 4096] (default (20, 20)); ics: K in [1, 1000] (default 10)
        theta_range, v_range: the starts (default: theta in (0, 1), v in each point's
            trapping region); transient, steps, max_period, recheck_factor: as classify
        recheck: "recurrence" (default: a start that joins a chaotic set on which an earlier
            start of the point stayed chaotic through its whole re-check stops there) or "full"
            (every start's whole re-check, as classify alone)
        certify: True: the exact orbit of (theta, v) (default the release state (0.5, 4))
            certified at each exact double point, with double's class; max_bits as for basin
        threads: worker threads (default: all cores)
        """
        d = self._scan(_texts(a_range=_range_text(a_range, "a_range"), eps_range=_range_text(eps_range, "eps_range"),
                              c_range=_range_text(c_range, "c_range"), grid=_grid_text(grid, "grid"), ics=ics,
                              theta_range=_range_text(theta_range, "theta_range"),
                              v_range=_range_text(v_range, "v_range"), transient=transient, steps=steps,
                              max_period=max_period, recheck_factor=recheck_factor, recheck=recheck,
                              certify="true" if certify else None, theta=theta, v=v, max_bits=max_bits,
                              threads=threads))
        y = d["y"]
        common = dict(a=d["a"], y_values=d[y], a_text=d["a_text"], y_text=d[y + "_text"], y=y,
                      certified=d["certified"])
        if d["certified"]:
            return Scan(**common, **_grid_fields(d))
        return Scan(**common, counts=d["counts"], count_classes=tuple(d["count_classes"]))

    def bifurcation(self, *, range: Tuple[Number, Number], theta: Number, v: Number, vary: str = "a",
                    samples: Optional[int] = None, transient: Optional[int] = None, record: Optional[int] = None,
                    carry: bool = False, certify: bool = False, max_bits: Optional[int] = None,
                    threads: Optional[int] = None) -> Bifurcation:
        """A bifurcation diagram: at each of K values of a, eps or c (LO and HI included), the
        orbit of (theta, v) after `transient` steps, `record` steps recorded
        (``bouncer bifurcation``). This model's value of the varied parameter is not used.

        range: (LO, HI), LO < HI; vary: "a" (default) | "eps" (constant) | "c" (veldep)
        theta, v: the start, valid for the model at LO
        samples: K in [1, 100000] (default 200); transient: N in [0, 1e8] (default 5000);
            record: M in [1, 1e6] (default 500); samples x record <= 5e7
        carry: each value starts from the last state of the previous one (one worker)
        certify: each column also certified (double only); max_bits as for basin
        threads: worker threads (default: all cores)
        """
        d = self._bifurcation(_texts(range=_range_text(range, "range"), theta=theta, v=v, vary=vary, samples=samples,
                                     transient=transient, record=record, carry="true" if carry else None,
                                     certify="true" if certify else None, max_bits=max_bits, threads=threads))
        return Bifurcation(**d)

    def portrait(self, theta: Union[Number, List[Number]], v: Union[Number, List[Number]], *,
                 steps: Optional[int] = None, transient: Optional[int] = None,
                 threads: Optional[int] = None) -> Portrait:
        """The orbits of several starts, as a phase portrait draws them (``bouncer portrait``,
        the same library call, reader and defaults; the picture's options change no point).

        theta, v: one start, or lists of as many phases (in [0, 1)) and velocities (at least
            the wall's velocity at each phase), 1..1000 starts
        steps: points per orbit, an integer in [1, 1e7] (default 1000); starts x steps <= 2e7
        transient: steps discarded first, an integer in [0, 1e8] (default 0; with 0 the start
            itself is the first row)
        threads: worker threads, an integer >= 1 (default: all cores); results do not depend on it
        """
        thetas = list(theta) if isinstance(theta, (list, tuple)) else [theta]
        vs = list(v) if isinstance(v, (list, tuple)) else [v]
        d = self._portrait(_texts(theta=thetas, v=vs, steps=steps, transient=transient, threads=threads))
        return Portrait(**d)

    def lyapunov_curve(self, range: Tuple[Number, Number], *, vary: str = "a", samples: Optional[int] = None,
                       ics: Optional[int] = None, theta: Optional[Number] = None, v: Optional[Number] = None,
                       transient: Optional[int] = None, steps: Optional[int] = None, blocks: Optional[int] = None,
                       max_period: Optional[int] = None, recheck_factor: Optional[int] = None,
                       threads: Optional[int] = None) -> ExponentCurve:
        """The leading Lyapunov exponent against a, eps or c (``bouncer lyapunov --vary``): at
        each of K values p_k = LO + (HI - LO) k/(K - 1), the exponent of ``lyapunov`` for each
        of the same N starts, and the class of that orbit where its window ended. This
        model's value of the varied parameter is not used.

        range: (LO, HI), LO < HI, both in the model's range; vary: "a" (default) | "eps"
            (constant model) | "c" (veldep model)
        samples: K in [1, 100000] (default 100)
        ics: N in [1, 1000] (default 1): (theta, v) first (default theta = 0.1, v = the wall's
            fastest upward velocity + 2), then an R2 low-discrepancy spread in the trapping
            region of every value
        transient: steps discarded first, in [0, 1e9] (default 1000); steps: steps measured,
            in [1, 1e9] (default 10000); blocks: of the error estimate, in [1, 10000] (default 20)
        max_period, recheck_factor: the classifier's, as classify (its transient is 0, its
            window 500 steps)
        threads: worker threads (default: all cores)
        """
        d = self._lyapunov_curve(_texts(range=_range_text(range, "range"), vary=vary, samples=samples, ics=ics,
                                        theta=theta, v=v, transient=transient, steps=steps, blocks=blocks,
                                        max_period=max_period, recheck_factor=recheck_factor, threads=threads))
        shape = tuple(d["shape"])
        return ExponentCurve(vary=d["vary"], value=d["value"], values=d["values"], starts=d["starts"],
                             lambda_=d["lambda_"], stderr=d["stderr"],
                             class_=_recode(d["class_"], d["class_names"], CLASSES, shape), period=d["period"],
                             max_lambda=d["max_lambda"], mean_lambda=d["mean_lambda"])
