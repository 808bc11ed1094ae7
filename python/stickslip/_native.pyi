"""Type stubs of the extension module ``stickslip._native`` (Rust, PyO3).

Every function takes the model by name and the parameters as ``(name,
value)`` pairs, and returns what the CLI prints with ``--json`` (as text);
the pure-Python package wraps it. Failures raise ``stickslip.errors`` types.
"""

from typing import List, Optional, Sequence, Tuple

Pairs = Sequence[Tuple[str, float]]
Columns = Tuple[List[float], List[float], List[float], List[float], List[float], List[float], List[int]]

def models() -> List[str]: ...
def params(model: str) -> List[Tuple[str, float, List[Tuple[str, float]], str, bool]]: ...
def describe(model: str, set: Pairs) -> Tuple[str, str]: ...
def check(path: str) -> str: ...

class Trajectory:
    def history(self, periods: int = 1, samples: int = 400) -> Optional[Columns]: ...
    def title(self) -> str: ...

def simulate(
    model: str, set: Pairs, start: Tuple[float, float, float], periods: Optional[int] = None
) -> Tuple[str, Optional[str], List[str], Trajectory]: ...
def orbit(
    model: str,
    set: Pairs,
    structure: str,
    periods: int = 1,
    guess: Optional[Tuple[float, float]] = None,
) -> Tuple[str, Optional[str], List[str], Trajectory]: ...
def sweep(
    model: str,
    set: Pairs,
    name: str,
    values: Sequence[float],
    starts: Optional[int] = None,
    every: Optional[int] = None,
    unstable: bool = True,
) -> str: ...
def orbit_diagram(
    model: str,
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
