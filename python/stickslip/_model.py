"""``Model``: a compiled-in model, chosen by name, and the analyses on it."""

from __future__ import annotations

import json
import warnings
from typing import Any, Dict, Iterable, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from ._results import Description, Motion, OrbitDiagram, Sweep
from .errors import InadmissibleError, InputError, NewtonError

Number = Union[int, float]


class Param(NamedTuple):
    """A parameter of a model: its default, its declared bounds as
    ``(op, value)`` pairs (``(">", 0.0)``), its doc, and whether this model
    takes it at run time (a scene folds some into constants)."""

    name: str
    default: float
    bounds: Tuple[Tuple[str, float], ...]
    doc: str
    free: bool


def models() -> List[str]:
    """The names of the compiled-in models and scenes (``model::scene``)."""
    return list(_native.models())


def check(path: str) -> str:
    """Check a model file as the build does; its model's name, or
    :class:`~stickslip.errors.ModelError` with every error at ``file:line:col``."""
    return str(_native.check(str(path)))


def _pairs(params: Dict[str, Number]) -> List[Tuple[str, float]]:
    out = []
    for name, value in params.items():
        try:
            out.append((str(name), float(value)))
        except (TypeError, ValueError):
            from .errors import ParamError

            raise ParamError(f"`{name}={value!r}`: `{value!r}` is not a number") from None
    return out


def _motion(answer: tuple) -> Motion:
    report, failure, notes, trajectory = answer
    result = Motion(json.loads(report), trajectory, notes)
    for note in notes:
        warnings.warn(note, stacklevel=3)
    if failure is not None:
        if result.kind == "not_converged":
            raise NewtonError(failure, result)
        raise InadmissibleError(failure, result)
    return result


class Model:
    """A compiled-in piecewise-linear model (``"paper"``, or ``"model::scene"``).

    Parameters are keyword arguments of every analysis (``W=5, Q0=70``); the
    others keep their defaults (``params``).
    """

    def __init__(self, name: str = "paper") -> None:
        self.name = str(name)
        rows = _native.params(self.name)  # raises ModelError for an unknown name
        self.params: Dict[str, Param] = {
            r[0]: Param(r[0], r[1], tuple(tuple(b) for b in r[2]), r[3], r[4]) for r in rows
        }

    def __repr__(self) -> str:
        return f"Model({self.name!r})"

    def describe(self, **params: Number) -> Description:
        """Domains, boundaries and mappings at the parameters (``stickslip describe``)."""
        text, data = _native.describe(self.name, _pairs(params))
        return Description(text, json.loads(data))

    def simulate(
        self,
        start: Sequence[Number] = (0.0, 0.0, 0.0),
        periods: Optional[int] = None,
        **params: Number,
    ) -> Motion:
        """Simulate from ``start = (x, v, Wt)`` until the motion settles, and
        name and refine it (``stickslip simulate``); at most ``periods``
        forcing periods (default 3000)."""
        x, v, wt = _start(start)
        return _motion(_native.simulate(self.name, _pairs(params), (x, v, wt), periods))

    def orbit(
        self,
        structure: str,
        guess: Optional[Sequence[Number]] = None,
        periods: int = 1,
        **params: Number,
    ) -> Motion:
        """Solve ``structure`` (``"P_{3_31 0_11 3_13 4_33}"``, applied right to
        left) for its periodic motion of ``periods`` forcing periods by Newton,
        from ``guess = (Wt, x)`` (its first switching point) or seeded by
        simulation (``stickslip orbit``)."""
        g = None
        if guess is not None:
            vals = [float(u) for u in guess]
            if len(vals) != 2:
                raise InputError(f"guess {tuple(guess)!r}: expected (Wt, x)")
            g = (vals[0], vals[1])
        return _motion(_native.orbit(self.name, _pairs(params), str(structure), int(periods), g))

    def sweep(
        self,
        param: str,
        values: Union[Iterable[Number], np.ndarray],
        starts: Optional[int] = None,
        every: Optional[int] = None,
        unstable: bool = True,
        **fixed: Number,
    ) -> Sweep:
        """Follow the periodic motions along ``param`` over ``values`` (an
        increasing array, list or range; need not be evenly spaced), with the
        branches, transitions and bifurcations (``stickslip sweep``).
        ``starts``/``every``: the global search for coexisting motions;
        ``unstable=False`` gives the view without unstable motions."""
        grid = np.asarray(list(values) if not isinstance(values, np.ndarray) else values, dtype=float)
        if grid.ndim != 1:
            raise InputError(f"values: expected a 1-d sequence, got shape {grid.shape}")
        data = _native.sweep(
            self.name, _pairs(fixed), str(param), grid.tolist(), starts, every, bool(unstable)
        )
        return Sweep(json.loads(data))

    def orbit_diagram(
        self,
        param: str,
        start: Number,
        stop: Number,
        count: int,
        transient: Optional[int] = None,
        periods: Optional[int] = None,
        lyapunov: Optional[int] = None,
        branches: bool = True,
        **fixed: Number,
    ) -> OrbitDiagram:
        """The brute-force bifurcation diagram over ``count`` values of
        ``param`` from ``start`` to ``stop`` (``stickslip orbit-diagram``):
        ``transient`` forcing periods discarded, ``periods`` samples kept and
        ``lyapunov`` periods of the largest exponent at each value; with
        ``branches``, the sweep's periodic branches at the section."""
        data, notes = _native.orbit_diagram(
            self.name, _pairs(fixed), str(param), float(start), float(stop), int(count),
            transient, periods, lyapunov, bool(branches),
        )
        for note in notes:
            warnings.warn(note, stacklevel=2)
        return OrbitDiagram(json.loads(data), notes)


def _start(start: Sequence[Number]) -> Tuple[float, float, float]:
    try:
        vals = [float(u) for u in start]
    except (TypeError, ValueError):
        raise InputError(f"start {start!r}: expected (x, v, Wt)") from None
    if len(vals) != 3 or not all(np.isfinite(vals)):
        raise InputError(f"start {tuple(start)!r}: expected three finite numbers (x, v, Wt)")
    return vals[0], vals[1], vals[2]
