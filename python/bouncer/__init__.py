"""bouncer: the piecewise linear bouncer's exact impact map, certified, from Python.

Two layers over one C++ library (the native ``bouncer._core``):

The library, typed. ``Model(model=, a=, eps= | c=, wall=, precision=)`` is built once and
validated once; ``m.step(theta, v)`` is one step of the impact map (a Step),
``m.orbit(theta, v, steps)`` an orbit as numpy arrays filled in C++ (an Orbit), and
``m.classify``, ``m.lyapunov``, ``m.periodic``, ``m.continue_branch``,
``m.certify_sticking``, ``m.certify_periodic``, ``m.certify_chaos``, and the grids
``m.basin``, ``m.scan``, ``m.bifurcation``, ``m.portrait``, ``m.lyapunov_curve`` call the
library's analyses and return dataclasses (Classification, Lyapunov, PeriodicOrbit, Branch,
StickingCertificate, PeriodicCertificate, ChaosProof, Basin, Scan, Bifurcation, Portrait,
ExponentCurve), with the command line's defaults; ``check_certificate(text)`` replays a chaos
certificate in Arb (a CertificateCheck). Numbers are float in double, decimal
texts (str) in the other point precisions, Interval (exact ends ``lo``/``hi``,
``to_mpmath()``) in interval precisions.

The command line, in-process. ``run(command, **options)`` and the functions ``step``,
``orbit``, ``certify_sticking``, ``sweep``, ``periodic``, ``certify_periodic``,
``continue_branch``, ``lyapunov``, ``classify``, ``basin``, ``scan``, ``bifurcation`` run the
bouncer command of the same name in this process, with the same options, defaults,
validation and code as the command line, so an answer there is the command line's answer:
the result (a Result) carries the CLI's JSON fields, its provenance included, and
``result.command_line`` reruns it in a shell. Keyword arguments are named after the CLI's
options (``--theta-range`` is ``theta_range``); ranges are pairs (``a_range=(28, 30)``),
grids pairs (``grid=(200, 150)``), flags booleans. Tables come as numpy arrays: float64 for
doubles (bit for bit the CLI's), str for other precisions, int64 for integer columns (-1
where the CLI's field is empty), int8 codes into ``CLASSES`` for grid class labels. This
layer also reaches what the library does not offer as a typed call yet: precision sweeps,
parameter ranges of the certified commands, and the other commands through ``run``.

Both layers: decimal strings and ``decimal.Decimal`` are exact (``a="28.82"``); Python floats
are the exact decimal of their binary value (``0.1`` is 0.1000000000000000055511...). Bad
input raises ValueError with bouncer's one-line message (it names the option and the
allowed range); Ctrl-C raises KeyboardInterrupt and leaves no partial file; long
computations release the GIL.
"""

from . import _core
from ._cli import (
    CLASSES, Result, basin, bifurcation, certify_periodic, certify_sticking, classify, continue_branch, lyapunov,
    orbit, periodic, run, scan, step, sweep, to_mpmath,
)
from ._cli import _words  # the CLI's words for a call (tests/python compare with the executable)
from ._model import (
    EVENTS, Attractor, Attractors, Basin, Bifurcation, Branch, BranchEnd, CertificateCheck, ChaosProof, Classification,
    ExponentCurve, Interval, Lyapunov, Model, Number, Orbit, PeriodicCertificate, PeriodicOrbit, Portrait, Real, Scan,
    Step, StickingCertificate, Undecided, check_certificate,
)

__version__ = _core.version
__all__ = [
    # the library, typed
    "Model", "Step", "Orbit", "Interval", "Undecided", "EVENTS", "Number", "Real",
    "Classification", "Lyapunov", "PeriodicOrbit", "Branch", "BranchEnd", "StickingCertificate",
    "PeriodicCertificate", "Basin", "Scan", "Bifurcation", "Portrait", "ExponentCurve", "Attractor", "Attractors",
    "ChaosProof", "CertificateCheck", "check_certificate",
    # the command line, in-process
    "Result", "CLASSES", "run", "step", "orbit", "certify_sticking", "sweep", "periodic", "certify_periodic",
    "continue_branch", "lyapunov", "classify", "basin", "scan", "bifurcation", "to_mpmath",
]
