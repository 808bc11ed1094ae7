"""``Model``: a compiled-in model chosen by name, or a model file or text
loaded and compiled at run time, and the analyses on it."""

from __future__ import annotations

import json
import operator
import os
import tempfile
import warnings
from typing import Any, Dict, Iterable, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from ._results import Description, Equilibria, LawMotion, LawSweep, Motion, OrbitDiagram, Sweep
from ._study import Basins, Curves, Lyapunov, Map
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
    """A piecewise-linear model: compiled in (``Model("paper")``, or
    ``"model::scene"``), or a model file or text loaded and compiled to
    machine code at run time (:meth:`from_file`, :meth:`from_source`): the
    same analyses on either, no Rust toolchain needed for the second.

    Parameters are keyword arguments of every analysis (``W=5, Q0=70``); the
    others keep their defaults (``params``).
    """

    def __init__(self, name: str = "paper") -> None:
        self._load(("name", str(name), None))

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"], scene: Optional[str] = None) -> "Model":
        """The model of the file at ``path`` (or its scene ``scene``),
        checked as ``stickslip check`` checks it and compiled to machine code
        (once per distinct file content in the process); a file the checks
        reject raises :class:`~stickslip.errors.ModelError` with every error
        at ``file:line:col``."""
        model = cls.__new__(cls)
        model._load(("file", os.fspath(path), None if scene is None else str(scene)))
        return model

    @classmethod
    def from_source(cls, text: str, scene: Optional[str] = None) -> "Model":
        """The model written in ``text`` (a model file's content; ``scene``
        for one of its scenes), as :meth:`from_file` loads a file; errors are
        located at ``<source>:line:col``."""
        model = cls.__new__(cls)
        model._load(("source", str(text), None if scene is None else str(scene)))
        return model

    def _load(self, spec: Tuple[str, str, Optional[str]]) -> None:
        self._spec = spec
        # Raises ModelError for an unknown name or a rejected file.
        self.name: str = _native.name(spec)
        rows = _native.params(spec)
        self.params: Dict[str, Param] = {
            r[0]: Param(r[0], r[1], tuple(tuple(b) for b in r[2]), r[3], r[4]) for r in rows
        }

    def __repr__(self) -> str:
        kind, what, scene = self._spec
        if kind == "name":
            return f"Model({what!r})"
        scene_arg = "" if scene is None else f", scene={scene!r}"
        if kind == "file":
            return f"Model.from_file({what!r}{scene_arg})"
        return f"Model.from_source(<{self.name}>{scene_arg})"

    def describe(self, **params: Number) -> Description:
        """Domains, boundaries and mappings at the parameters (``stickslip describe``)."""
        text, data = _native.describe(self._spec, _pairs(params))
        return Description(text, json.loads(data))

    def simulate(
        self,
        start: Sequence[Number] = (0.0, 0.0, 0.0),
        periods: Optional[int] = None,
        **params: Number,
    ) -> Union[Motion, LawMotion]:
        """Simulate from ``start = (x, v, Wt)`` until the motion settles, and
        name and refine it (``stickslip simulate``); at most ``periods``
        forcing periods (default 3000). A model with a smooth law (no
        scene) is integrated and gives a :class:`LawMotion`: steady sliding
        or a self-excited cycle when unforced (``periods`` then counts
        returns to the section ``v = 0``), a periodic motion when forced."""
        x, v, wt = _start(start)
        n = None if periods is None else int(periods)
        law = _native.simulate_law(self._spec, _pairs(params), (x, v, wt), n)
        if law is not None:
            return LawMotion(json.loads(law))
        return _motion(_native.simulate(self._spec, _pairs(params), (x, v, wt), periods))

    def orbit(
        self,
        structure: str,
        guess: Optional[Sequence[Number]] = None,
        periods: Optional[int] = None,
        **params: Number,
    ) -> Motion:
        """Solve ``structure`` (``"P_{3_31 0_11 3_13 4_33}"``, applied right to
        left; a repeated block as ``"(P_{1_11 0_11 2_11})^{×4}"``) for its
        periodic motion of ``periods`` forcing periods (default 1, or ``k``
        for a block repeated ``k`` times) by Newton, from ``guess = (Wt, x)``
        (its first switching point) or seeded by simulation (``stickslip
        orbit``)."""
        g = None
        if guess is not None:
            vals = [float(u) for u in guess]
            if len(vals) != 2:
                raise InputError(f"guess {tuple(guess)!r}: expected (Wt, x)")
            g = (vals[0], vals[1])
        n = None if periods is None else int(periods)
        return _motion(_native.orbit(self._spec, _pairs(params), str(structure), n, g))

    def sweep(
        self,
        param: str,
        values: Union[Iterable[Number], np.ndarray],
        starts: Optional[int] = None,
        every: Optional[int] = None,
        unstable: bool = True,
        max_mappings: Optional[int] = None,
        max_period: Optional[int] = None,
        **fixed: Number,
    ) -> Union[Sweep, LawSweep]:
        """Follow the periodic motions along ``param`` over ``values`` (an
        increasing array, list or range; need not be evenly spaced), with the
        branches, transitions and bifurcations (``stickslip sweep``).
        ``starts``/``every``: the global search for coexisting motions;
        ``unstable=False`` gives the view without unstable motions;
        ``max_mappings``: follow no branch of a motion of more mappings
        (a period-doubling cascade into chaos otherwise follows hundreds);
        ``max_period``: follow no branch born by period doubling of more
        forcing periods (default 16; 0: no limit), listed in ``cuts``; the
        cascades and their accumulation points are in ``cascades``.

        A model with a smooth law (no scene) is swept as the law itself, and
        gives a :class:`LawSweep`: steady sliding and every self-excited
        cycle at each value, stable and unstable, with the Hopf point and
        the stick-slip cycle's end located (the forcing must be off; the
        search options do not apply)."""
        grid = np.asarray(list(values) if not isinstance(values, np.ndarray) else values, dtype=float)
        if grid.ndim != 1:
            raise InputError(f"values: expected a 1-d sequence, got shape {grid.shape}")
        law = _native.sweep_law(self._spec, _pairs(fixed), str(param), grid.tolist())
        if law is not None:
            return LawSweep(json.loads(law))
        data = _native.sweep(
            self._spec, _pairs(fixed), str(param), grid.tolist(), starts, every, bool(unstable),
            max_mappings, max_period,
        )
        return Sweep(json.loads(data))

    def equilibria(
        self,
        along: Optional[Tuple[str, Number, Number, int]] = None,
        **fixed: Number,
    ) -> Equilibria:
        """Steady sliding of the unforced model (the forcing amplitude must
        be 0), its exact eigenvalues and stability (``stickslip
        equilibria``): at the parameters ``fixed``, or along ``along = (name,
        from, to, count)`` with every change of stability located (the Hopf
        point of a smooth law, the breakpoint of a piecewise one). A model
        with a smooth law is taken as the law itself."""
        rng = None
        if along is not None:
            if len(along) != 4:
                raise InputError(f"along: expected (name, from, to, count), got {along!r}")
            rng = (str(along[0]), float(along[1]), float(along[2]), int(along[3]))
        data = _native.equilibria(self._spec, _pairs(fixed), rng)
        return Equilibria(json.loads(data))

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
            self._spec, _pairs(fixed), str(param), float(start), float(stop), int(count),
            transient, periods, lyapunov, bool(branches),
        )
        for note in notes:
            warnings.warn(note, stacklevel=2)
        return OrbitDiagram(json.loads(data), notes)

    def map(
        self,
        x: Tuple[str, Number, Number, int],
        y: Tuple[str, Number, Number, int],
        method: str = "continuation",
        out: Optional[Union[str, "os.PathLike[str]"]] = None,
        resume: bool = False,
        progress: bool = True,
        **fixed: Number,
    ) -> Map:
        """Which motions exist at each point of the grid ``x × y``, each axis
        ``(name, from, to, count)`` (``("W", 0.2, 8, 100)``), the other
        parameters at ``fixed`` (``stickslip map``), on all cores.

        ``method``: ``"continuation"`` (neighbours' motions continued by
        Newton) or ``"simulation"`` (every point simulated; slower). The map
        is written point by point to the CSV file ``out`` (a temporary file,
        deleted after reading, when ``None``); ``resume=True`` continues an
        interrupted run from it. ``progress=False`` hides the progress bar."""
        xa = _axis("x", x, named=True)
        ya = _axis("y", y, named=True)
        with _output(out, "map.csv") as path:
            data, labels = _native.map(
                self._spec, _pairs(fixed), xa, ya, path, str(method), bool(resume), bool(progress)
            )
            result = json.loads(data)
        result["file"] = None if out is None else str(out)
        return Map(result, labels)

    def curves(
        self,
        x: Tuple[str, Number, Number],
        y: Tuple[str, Number, Number],
        seed: Optional[Any] = None,
        at: Optional[Any] = None,
        count: Optional[int] = None,
        spread: Optional[int] = None,
        max_mappings: Optional[int] = None,
        probes: Optional[int] = None,
        max_partners: Optional[int] = None,
        edges: bool = True,
        **fixed: Number,
    ) -> Curves:
        """The transition curves over the box ``x × y``, each side
        ``(name, from, to)``, the other parameters at ``fixed``
        (``stickslip curves``).

        ``seed``: seed lines, ``{"Q0": 70}`` (the sweep along ``x`` at
        ``Q0 = 70``; a list of values gives several lines) or ``[("Q0", 70),
        ("W", 5)]``; default: the box's middle horizontal line. ``at``: lines
        whose crossings with every curve are solved exactly, given alike.
        ``count``: grid values of each line's sweep (default 100);
        ``spread``: extra seed lines each way (default 3);
        ``max_mappings``: the longest motion whose transitions are traced
        (default 24; ``--max-mappings``); ``probes``: short sweeps across
        each curve at this many places, finding the bands no line crosses
        (default 0, off; ``--probes``); ``max_partners``: at most this
        many curves traced by branch switching at codimension-two points,
        the second condition's curve through each (default 200, 0 turns it
        off; ``--max-partners``); ``edges``: sweep the box's four
        edges too, where every curve that leaves the box crosses (default
        True; ``False`` is ``--no-edges``)."""
        data = _native.curves(
            self._spec,
            _pairs(fixed),
            _side("x", x),
            _side("y", y),
            _lines("seed", seed),
            _lines("at", at),
            _count("count", count, 0),
            _count("spread", spread, 0),
            _count("max_mappings", max_mappings, 0),
            _count("probes", probes, 0),
            _count("max_partners", max_partners, 0),
            bool(edges),
        )
        return Curves(json.loads(data))

    def lyapunov(
        self,
        start: Sequence[Number] = (0.0, 0.0, 0.0),
        transient: Optional[int] = None,
        periods: Optional[int] = None,
        **params: Number,
    ) -> Lyapunov:
        """The Lyapunov spectrum of the stroboscopic map along the trajectory
        from ``start = (x, v, Wt)``, from the exact tangent map, with a verdict
        (``stickslip lyapunov``): ``transient`` forcing periods discarded
        (default 1000), then ``periods`` accumulated (default 10000; 10 or
        more for an error estimate)."""
        data = _native.lyapunov(
            self._spec,
            _pairs(params),
            _start(start),
            _count("transient", transient, 0),
            _count("periods", periods, 0),
        )
        return Lyapunov(json.loads(data))

    def basins(
        self,
        x: Tuple[Number, Number, int],
        y: Tuple[Number, Number, int],
        phase: Number = 0.0,
        samples: int = 1000,
        seed: int = 1,
        periods: Optional[int] = None,
        lyapunov: Optional[int] = None,
        out: Optional[Union[str, "os.PathLike[str]"]] = None,
        resume: bool = False,
        progress: bool = True,
        **params: Number,
    ) -> Basins:
        """Which attractor each start ``(x, v)`` at the phase ``Wt = phase``
        reaches, over the grid of displacements ``x = (from, to, count)`` and
        velocities ``y = (from, to, count)``, and the basin stability from
        ``samples`` random starts in the same box (seeded by ``seed``)
        (``stickslip basins``), on all cores. ``periods``: forcing periods
        simulated at most from each start (default 600); ``lyapunov``: those
        of the exponent of a start that never settles (default 2000; 0: none).

        The starts are written one by one to the CSV file ``out`` (a
        temporary file, deleted after reading, when ``None``); ``resume=True``
        continues an interrupted run from it. ``progress=False`` hides the
        progress bar."""
        xa = _axis("x", x, named=False)
        va = _axis("y", y, named=False)
        try:
            ph = float(phase)
        except (TypeError, ValueError):
            raise InputError(f"phase {phase!r}: expected a number") from None
        with _output(out, "basins.csv") as path:
            data, xs, vs, ids, exps = _native.basins(
                self._spec,
                _pairs(params),
                xa,
                va,
                path,
                ph,
                _count("samples", samples, 0),
                _count("seed", seed, 0),
                _count("periods", periods, 0),
                _count("lyapunov", lyapunov, 0),
                bool(resume),
                bool(progress),
            )
        result = json.loads(data)
        if out is None:
            result["file"] = None
        return Basins(result, xs, vs, ids, exps)


class _output:
    """The path of an output file: ``out``, or one in a temporary folder
    removed (with the file) on exit."""

    def __init__(self, out: Any, name: str) -> None:
        self._out = out
        self._name = name
        self._dir: Optional[tempfile.TemporaryDirectory] = None

    def __enter__(self) -> str:
        if self._out is not None:
            return os.fspath(self._out)
        self._dir = tempfile.TemporaryDirectory(prefix="stickslip-")
        return os.path.join(self._dir.name, self._name)

    def __exit__(self, *exc: Any) -> None:
        if self._dir is not None:
            self._dir.cleanup()


def _count(what: str, n: Optional[int], least: int) -> Optional[int]:
    """An integer argument at least ``least`` (``None`` passes through)."""
    if n is None:
        return None
    try:
        k = operator.index(n)
    except TypeError:
        raise InputError(f"{what}={n!r}: expected an integer") from None
    if k < least:
        raise InputError(f"{what}={k}: must be at least {least}")
    return k


def _axis(what: str, axis: Any, named: bool) -> tuple:
    """``(name, from, to, count)`` (or ``(from, to, count)``), checked for shape and types."""
    shape = "(name, from, to, count)" if named else "(from, to, count)"
    try:
        parts = list(axis)
    except TypeError:
        raise InputError(f"{what}={axis!r}: expected {shape}") from None
    if len(parts) != (4 if named else 3):
        raise InputError(f"{what}={tuple(parts)!r}: expected {shape}")
    name = str(parts.pop(0)) if named else None
    try:
        lo, hi = float(parts[0]), float(parts[1])
        n = operator.index(parts[2])
    except (TypeError, ValueError):
        raise InputError(f"{what}={tuple(axis)!r}: expected {shape} with an integer count") from None
    return (name, lo, hi, n) if named else (lo, hi, n)


def _side(what: str, side: Any) -> Tuple[str, float, float]:
    """``(name, from, to)`` of a box."""
    try:
        name, lo, hi = side
        return str(name), float(lo), float(hi)
    except (TypeError, ValueError):
        raise InputError(f"{what}={side!r}: expected (name, from, to)") from None


def _lines(what: str, lines: Any) -> List[Tuple[str, float]]:
    """Lines ``{"Q0": 70}``, ``{"Q0": [70, 90]}`` or ``[("Q0", 70), ...]`` as pairs."""
    if lines is None:
        return []
    items = lines.items() if isinstance(lines, dict) else lines
    out: List[Tuple[str, float]] = []
    try:
        for name, values in items:
            vals = values if isinstance(values, (list, tuple, np.ndarray)) else [values]
            out.extend((str(name), float(v)) for v in vals)
    except (TypeError, ValueError):
        raise InputError(
            f"{what}={lines!r}: expected {{name: value or values}} or [(name, value), ...]"
        ) from None
    return out


def _start(start: Sequence[Number]) -> Tuple[float, float, float]:
    try:
        vals = [float(u) for u in start]
    except (TypeError, ValueError):
        raise InputError(f"start {start!r}: expected (x, v, Wt)") from None
    if len(vals) != 3 or not all(np.isfinite(vals)):
        raise InputError(f"start {tuple(start)!r}: expected three finite numbers (x, v, Wt)")
    return vals[0], vals[1], vals[2]
