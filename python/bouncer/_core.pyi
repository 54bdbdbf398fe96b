# Type stubs of the native module (python/module.cpp). The typed layer over it is
# bouncer/_model.py (annotated inline); these are the classes it re-exports.
from typing import Dict, List, Optional, Tuple, Union

import numpy as np

version: str
commit: str

class Undecided(ArithmeticError):
    """An interval step whose branch could not be decided for the whole enclosure."""

class Interval:
    lo: str
    hi: str
    def __init__(self, lo: str, hi: str) -> None: ...
    def to_floats(self) -> Tuple[float, float]: ...
    def to_mpmath(self, bits: Optional[int] = ...) -> object: ...

_Real = Union[float, str, Interval]

class Step:
    theta: _Real
    v: _Real
    tau: _Real
    event: str
    periods: int
    segment: int
    wall: str
    corner: bool
    indirect: Optional[bool]
    stick_segment: Optional[int]
    stuck_theta: Optional[_Real]
    stuck_v: Optional[_Real]
    passed_upward_turn: bool
    phase_bits: int
    @property
    def state(self) -> Tuple[_Real, _Real]: ...

class Orbit:
    n: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    event: np.ndarray
    tau: np.ndarray
    periods: np.ndarray
    segment: np.ndarray
    wall: np.ndarray
    corner: np.ndarray
    indirect: np.ndarray
    stick_segment: np.ndarray
    stuck_theta: np.ndarray
    stuck_v: np.ndarray
    passed_upward_turn: np.ndarray
    phase_bits: np.ndarray
    status: str
    steps_done: int
    reason: str
    phase_lost_at: Optional[int]
    lohner_fallbacks: Optional[int]
    precision: str
    def __len__(self) -> int: ...

class Model:
    def __init__(self, options: Dict[str, List[str]]) -> None: ...
    def step(self, theta: Union[str, int, float, object], v: Union[str, int, float, object]) -> Step: ...
    @property
    def options(self) -> Dict[str, Union[str, List[str]]]: ...
    @property
    def precision(self) -> str: ...
    @property
    def bits(self) -> int: ...
    @property
    def model(self) -> str: ...
    @property
    def a(self) -> str: ...
    @property
    def eps(self) -> Optional[str]: ...
    @property
    def c(self) -> Optional[str]: ...
    @property
    def wall(self) -> str: ...
    def _orbit(self, options: Dict[str, List[str]]) -> Orbit: ...
    def _classify(self, options: Dict[str, List[str]]) -> dict: ...
    def _lyapunov(self, options: Dict[str, List[str]]) -> dict: ...
    def _periodic(self, options: Dict[str, List[str]]) -> dict: ...
    def _continue_branch(self, options: Dict[str, List[str]]) -> dict: ...
    def _certify_sticking(self, options: Dict[str, List[str]]) -> dict: ...
    def _certify_periodic(self, options: Dict[str, List[str]]) -> dict: ...

def run(words: List[str]) -> dict: ...
