"""Type stubs of the extension module ``stickslip._native`` (Rust, PyO3).

Every function takes the model as a spec, ``("name", NAME, None)``,
``("file", PATH, SCENE)`` or ``("source", TEXT, SCENE)``, and the parameters
as ``(name, value)`` pairs, and returns what the CLI prints with ``--json`` (as text);
the pure-Python package wraps it. Failures raise ``stickslip.errors`` types.
"""

from typing import List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

Pairs = Sequence[Tuple[str, float]]
ModelSpec = Tuple[str, str, Optional[str]]
Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]
# t, Wt, x, v, a, F (float64) and domain (int64), moved from Rust without a copy.
Columns = Tuple[Floats, Floats, Floats, Floats, Floats, Floats, Ints]

def models() -> List[str]: ...
def params(model: ModelSpec) -> List[Tuple[str, float, List[Tuple[str, float]], str, bool]]: ...
def name(model: ModelSpec) -> str: ...
def describe(model: ModelSpec, set: Pairs) -> Tuple[str, str]: ...
def check(path: str) -> str: ...

class Trajectory:
    def history(self, periods: int = 1, samples: int = 400) -> Optional[Columns]: ...
    def title(self) -> str: ...

def simulate(
    model: ModelSpec, set: Pairs, start: Tuple[float, float, float], periods: Optional[int] = None
) -> Tuple[str, Optional[str], List[str], Trajectory]: ...
def orbit(
    model: ModelSpec,
    set: Pairs,
    structure: str,
    periods: Optional[int] = None,
    guess: Optional[Tuple[float, float]] = None,
) -> Tuple[str, Optional[str], List[str], Trajectory]: ...
def sweep(
    model: ModelSpec,
    set: Pairs,
    name: str,
    values: Sequence[float],
    starts: Optional[int] = None,
    every: Optional[int] = None,
    unstable: bool = True,
    max_mappings: Optional[int] = None,
    max_period: Optional[int] = None,
) -> str: ...
def orbit_diagram(
    model: ModelSpec,
    set: Pairs,
    name: str,
    from_: float,
    to: float,
    count: int,
    transient: Optional[int] = None,
    periods: Optional[int] = None,
    lyapunov: Optional[int] = None,
    branches: bool = True,
) -> Tuple[str, List[str]]: ...

# The analyses over two parameters and over starts (`python/src/study/`).
Axis = Tuple[str, float, float, int]

def map(
    model: ModelSpec,
    set: Pairs,
    x: Axis,
    y: Axis,
    out: str,
    method: str = "continuation",
    resume: bool = False,
    progress: bool = True,
) -> Tuple[str, List[str]]:
    """The map as JSON (``Map.to_dict()`` without ``file``), and each point's label."""
    ...
def curves(
    model: ModelSpec,
    set: Pairs,
    x: Tuple[str, float, float],
    y: Tuple[str, float, float],
    seeds: Pairs = ...,
    at: Pairs = ...,
    count: Optional[int] = None,
    spread: Optional[int] = None,
    max_mappings: Optional[int] = None,
    probes: Optional[int] = None,
    max_partners: Optional[int] = None,
    edges: bool = True,
) -> str: ...
def simulate_law(
    model: ModelSpec,
    set: Pairs,
    start: Tuple[float, float, float],
    periods: Optional[int] = None,
) -> Optional[str]: ...
def sweep_law(
    model: ModelSpec,
    set: Pairs,
    name: str,
    values: List[float],
) -> Optional[str]: ...
def equilibria(
    model: ModelSpec,
    set: Pairs,
    range: Optional[Tuple[str, float, float, int]] = None,
) -> str: ...
def lyapunov(
    model: ModelSpec,
    set: Pairs,
    start: Tuple[float, float, float],
    transient: Optional[int] = None,
    periods: Optional[int] = None,
) -> str: ...
def basins(
    model: ModelSpec,
    set: Pairs,
    x: Tuple[float, float, int],
    v: Tuple[float, float, int],
    out: str,
    phase: float = 0.0,
    samples: int = 1000,
    seed: int = 1,
    periods: Optional[int] = None,
    lyapunov: Optional[int] = None,
    resume: bool = False,
    progress: bool = True,
) -> Tuple[str, Floats, Floats, Ints, Floats]:
    """The JSON of ``basins --json``; every start in index order (numpy
    arrays): x, v, the attractor's position in the JSON's list, the exponent
    (NaN: none)."""
    ...
