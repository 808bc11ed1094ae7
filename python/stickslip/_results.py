"""Result objects: the CLI's JSON (``to_dict()``), with numpy arrays for the
numbers a notebook plots, and ``to_pandas()`` for the tabular ones."""

from __future__ import annotations

import copy
from typing import Any, Dict, List, Optional

import numpy as np


def _pandas() -> Any:
    try:
        import pandas  # type: ignore[import-not-found]
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_pandas() needs pandas: pip install pandas") from e
    return pandas


def _complex(pairs: Optional[List[List[float]]]) -> np.ndarray:
    """``[[re, im], ...]`` as a complex array (empty for ``None``)."""
    if not pairs:
        return np.zeros(0, dtype=complex)
    a = np.asarray(pairs, dtype=float)
    return a[:, 0] + 1j * a[:, 1]


def _float(v: Optional[float]) -> float:
    """A JSON number, ``nan`` for ``null``."""
    return np.nan if v is None else float(v)


def _floats(vs: List[Optional[float]]) -> np.ndarray:
    return np.array([_float(v) for v in vs], dtype=float)


class Result:
    """A result: its JSON as the CLI prints it with ``--json``."""

    def __init__(self, data: Dict[str, Any]) -> None:
        self._data = data

    def to_dict(self) -> Dict[str, Any]:
        """The result as the CLI's ``--json`` gives it (a deep copy)."""
        return copy.deepcopy(self._data)

    def __getitem__(self, key: str) -> Any:
        return self._data[key]


class History(Result):
    """A motion in time: numpy arrays ``t, Wt, x, v, a, F, domain`` (one
    sample per row; at a switching instant the segment ending there and the
    one starting there each give a sample). ``domain`` 0 is stick; ``F`` is
    the friction force."""

    COLUMNS = ("t", "Wt", "x", "v", "a", "F", "domain")

    def __init__(self, columns: tuple) -> None:
        # numpy arrays from the extension (moved from Rust, not copied);
        # ``np.asarray`` keeps them as they are.
        t, wt, x, v, a, f, domain = columns
        self.t = np.asarray(t, dtype=float)
        self.Wt = np.asarray(wt, dtype=float)
        self.x = np.asarray(x, dtype=float)
        self.v = np.asarray(v, dtype=float)
        self.a = np.asarray(a, dtype=float)
        self.F = np.asarray(f, dtype=float)
        self.domain = np.asarray(domain, dtype=np.int64)
        self._dict: Optional[Dict[str, Any]] = None

    @property
    def _data(self) -> Dict[str, Any]:  # type: ignore[override]
        # The lists of ``to_dict()``, made on first use only.
        if self._dict is None:
            self._dict = {c: getattr(self, c).tolist() for c in self.COLUMNS}
        return self._dict

    def to_dict(self) -> Dict[str, Any]:
        """The columns as lists of Python numbers, as the CLI's JSON gives
        them (new lists each call: ``tolist()`` copies, no deep copy needed)."""
        return {c: getattr(self, c).tolist() for c in self.COLUMNS}

    def __len__(self) -> int:
        return len(self.t)

    def to_pandas(self) -> Any:
        """A DataFrame with one column per array."""
        return _pandas().DataFrame({c: getattr(self, c) for c in self.COLUMNS})

    def __repr__(self) -> str:
        return f"History({len(self)} samples, t = {self.t[0]:.6g} .. {self.t[-1]:.6g})"


class Motion(Result):
    """What ``simulate`` or ``orbit`` found.

    ``kind`` is ``periodic``, ``neutral_family``, ``NM`` (no boundary
    contact), ``stick`` (permanent), ``autonomous_cycle``, or, carried by an
    exception, ``inadmissible`` or ``not_converged``. For a periodic motion:
    ``structure`` (``P_{...}``), ``N`` (forcing periods per cycle),
    ``points`` (an ``m × 3`` array of switching points ``Wt, x, v``, with
    ``boundaries`` and ``mappings`` naming each), ``eigenvalues`` (complex),
    ``stable`` and ``admissible``. For an autonomous stick-slip cycle:
    ``period``, ``stick_time``, ``multiplier`` (the nontrivial Floquet
    multiplier, the trivial 1 removed) and ``stable``. For an NM of an
    unforced model: ``steady_sliding``, the equilibrium it rests at (``x``,
    ``eigenvalues``, ``verdict``, ``margin``), and ``stable``.
    """

    def __init__(self, data: Dict[str, Any], trajectory: Any, notes: List[str]) -> None:
        super().__init__(data)
        self._trajectory = trajectory
        self.notes = list(notes)
        self.kind: str = data["kind"]
        self.structure: Optional[str] = data.get("structure")
        self.N: Optional[int] = data.get("N")
        points = data.get("points") or []
        self.points = np.array([[p["Wt"], p["x"], p["v"]] for p in points], dtype=float).reshape(
            len(points), 3
        )
        self.boundaries: List[str] = [p["boundary"] for p in points]
        self.mappings: List[str] = [p["mapping"] for p in points]
        self.eigenvalues = _complex(data.get("eigenvalues"))
        self.stable: Optional[bool] = data.get("stable")
        self.admissible: Optional[bool] = data.get("admissible")
        self.violations: List[Dict[str, Any]] = data.get("violations", [])
        self.params: Dict[str, float] = data.get("params", {})
        self.period: Optional[float] = data.get("period")
        self.stick_time: Optional[float] = data.get("stick")
        self.multiplier: Optional[float] = data.get("multiplier")
        self.steady_sliding: Optional[Dict[str, Any]] = data.get("steady_sliding")
        if self.kind == "autonomous_cycle" and self.multiplier is not None:
            self.stable = abs(self.multiplier) < 1.0
        if self.steady_sliding is not None:
            self.stable = self.steady_sliding["verdict"] == "stable"

    @property
    def title(self) -> str:
        """The figure title the CLI gives this result."""
        return str(self._trajectory.title())

    def history(self, periods: int = 1, samples: int = 400) -> History:
        """``periods`` cycles of the motion (a periodic motion repeats its
        exact cycle; NM, stick and an autonomous cycle are simulated over a
        window ``periods`` times longer), ``samples`` per forcing period."""
        columns = self._trajectory.history(periods, samples)
        if columns is None:
            from .errors import InputError

            raise InputError("there is no motion")
        return History(columns)

    def to_pandas(self) -> Any:
        """The switching points as a DataFrame: ``k, Wt, x, v, boundary, mapping``."""
        return _pandas().DataFrame(
            {
                "k": np.arange(len(self.points)),
                "Wt": self.points[:, 0],
                "x": self.points[:, 1],
                "v": self.points[:, 2],
                "boundary": self.boundaries,
                "mapping": self.mappings,
            }
        )

    def __repr__(self) -> str:
        if self.structure is not None:
            return f"Motion({self.kind}, {self.structure}, N = {self.N}, stable = {self.stable})"
        return f"Motion({self.kind})"


class Description(Result):
    """``describe``: domains, boundaries and mappings at the parameters;
    ``str()`` is the CLI's table."""

    def __init__(self, text: str, data: Dict[str, Any]) -> None:
        super().__init__(data)
        self._text = text

    def __str__(self) -> str:
        return self._text

    def to_pandas(self, table: str = "domains") -> Any:
        """One of ``describe``'s tables as a DataFrame: ``"domains"`` (one
        row per domain: ``label``, ``v_min``, ``v_max``, ``two_d``, ``c``,
        ``b``, ``regime``) or ``"boundaries"`` (``label``, ``v``, ``stick``,
        ``static_bound``); ``None`` in the JSON is NaN."""
        if table not in ("domains", "boundaries"):
            from .errors import InputError

            raise InputError(f"table {table!r}: expected 'domains' or 'boundaries'")
        rows = [{k: (np.nan if v is None else v) for k, v in r.items()} for r in self._data[table]]
        return _pandas().DataFrame(rows)

    def _repr_pretty_(self, p: Any, cycle: bool) -> None:  # IPython
        p.text(self._text)


class LawMotion(Result):
    """What a smooth law settles to, integrated (``stickslip simulate
    --json`` of a model with a smooth law and no scene): ``kind`` is
    ``"steady_sliding"`` (``equilibrium``), ``"cycle"`` (a self-excited
    cycle: ``x`` on the section ``v = 0``, ``period``, ``stick``,
    ``multiplier``, ``verdict``, ``events``) or ``"periodic"`` (forced:
    ``periods``, ``phase``, ``x``, ``v``, ``sticks``, ``multipliers``,
    ``verdict``, ``events``). ``period``, ``stick`` and ``multiplier`` are
    also attributes of a cycle; ``stable`` of every kind."""

    def __init__(self, data: Dict[str, Any]) -> None:
        super().__init__(data)
        self.kind: str = data["kind"]
        if self.kind == "steady_sliding":
            verdict = data["equilibrium"]["verdict"]
        elif self.kind == "cycle":
            cycle = data["cycle"]
            verdict = cycle["verdict"]
            self.period: float = cycle["period"]
            self.stick: float = cycle["stick"]
            self.multiplier: float = cycle["multiplier"]
        else:
            verdict = data["verdict"]
        self.stable: bool = verdict == "stable"

    def to_pandas(self) -> Any:
        """One row: the ``kind``, ``stable``, and the cycle's ``period``,
        ``stick``, ``multiplier`` and section ``x`` (NaN where the kind has
        none), or the forced motion's ``periods``, ``x`` and ``v``."""
        row: Dict[str, Any] = {"kind": self.kind, "stable": self.stable}
        d = self._data.get("cycle", self._data)
        for key in ("period", "stick", "multiplier", "x", "v", "periods"):
            row[key] = d.get(key, np.nan)
        return _pandas().DataFrame([row])

    def __repr__(self) -> str:
        if self.kind == "cycle":
            return f"LawMotion(cycle, period={self.period!r}, stick={self.stick!r}, stable={self.stable})"
        return f"LawMotion({self.kind}, stable={self.stable})"


class Equilibria(Result):
    """Steady sliding of an unforced model (``stickslip equilibria --json``):
    ``model``, ``param``, ``points`` (at each value: ``equilibrium`` with
    ``x``, ``eigenvalues``, ``verdict`` and ``margin``, its ``seat``, or why
    there is ``none``) and ``changes`` (every change of stability between
    grid values, located: ``at``, ``before``, ``after``, ``loss``, ``what``); ``values``
    and ``x`` (``nan`` where there is no equilibrium) as numpy arrays."""

    def __init__(self, data: Dict[str, Any]) -> None:
        super().__init__(data)
        self.model: str = data["model"]
        self.param: str = data["param"]
        self.points: List[Dict[str, Any]] = data["points"]
        self.changes: List[Dict[str, Any]] = data["changes"]
        self.values = np.array([p["value"] for p in self.points], dtype=float)
        self.x = np.array(
            [p["equilibrium"]["x"] if p.get("equilibrium") else np.nan for p in self.points],
            dtype=float,
        )

    def to_pandas(self) -> Any:
        """One row per value: ``value``, ``x``, ``verdict``, ``margin``,
        ``seat``, ``none`` (why there is no equilibrium; NaN values there)."""
        rows = []
        for p in self.points:
            e = p.get("equilibrium") or {}
            rows.append(
                {
                    "value": p["value"],
                    "x": e.get("x", np.nan),
                    "verdict": e.get("verdict"),
                    "margin": e.get("margin", np.nan),
                    "seat": p.get("seat"),
                    "none": p.get("none"),
                }
            )
        return _pandas().DataFrame(rows)


class LawSweep(Equilibria):
    """A smooth law itself along a parameter (``stickslip sweep --json`` of
    a model with a smooth law and no scene): as :class:`Equilibria`
    (``model``, ``param``, ``points``, ``changes``, ``values``, the rest
    position ``x``), each point also with ``cycles``, every self-excited
    cycle on the section ``v = 0`` (``x``, ``period``, ``stick``,
    ``multiplier``, ``verdict``), and ``stick_slip`` (where the stick-slip
    cycle appears or vanishes, located: ``at``, ``below``, ``what``)."""

    def __init__(self, data: Dict[str, Any]) -> None:
        super().__init__(data)
        self.stick_slip: List[Dict[str, Any]] = data["stick_slip"]

    def to_pandas(self) -> Any:
        """One row per motion at each value: ``value``, ``kind``
        (``"steady_sliding"``, ``"stick_slip"`` or ``"slip"``), ``x`` (the
        rest position, or the cycle's point on ``v = 0``), ``stable``,
        and the cycle's ``period``, ``stick`` and ``multiplier`` (NaN for
        steady sliding)."""
        rows = []
        for p in self.points:
            e = p.get("equilibrium")
            if e:
                rows.append(
                    {
                        "value": p["value"],
                        "kind": "steady_sliding",
                        "x": e["x"],
                        "stable": e["verdict"] == "stable",
                        "period": np.nan,
                        "stick": np.nan,
                        "multiplier": np.nan,
                    }
                )
            for c in p["cycles"]:
                rows.append(
                    {
                        "value": p["value"],
                        "kind": "stick_slip" if c["stick"] > 0 else "slip",
                        "x": c["x"],
                        "stable": c["verdict"] == "stable",
                        "period": c["period"],
                        "stick": c["stick"],
                        "multiplier": c["multiplier"],
                    }
                )
        return _pandas().DataFrame(rows)

    def __repr__(self) -> str:
        return f"LawSweep({self.model}, {self.param}, {len(self.points)} values)"


class Sweep(Result):
    """A sweep of one parameter (``stickslip sweep --json``): ``param``, the
    grid ``values``, ``points`` (the motions at each value), ``branches``
    (followed by arclength continuation, unstable parts kept), ``transitions``,
    ``bifurcations``, ``cuts`` (branches born by period doubling beyond
    ``max_period``, not followed) and ``cascades`` (the period-doubling
    cascades with their accumulation points), each a list of dicts as in the
    CLI's JSON."""

    def __init__(self, data: Dict[str, Any]) -> None:
        super().__init__(data)
        self.param: str = data["param"]
        self.points: List[Dict[str, Any]] = data["points"]
        self.values = np.array([p[self.param] for p in self.points], dtype=float)
        self.branches: List[Dict[str, Any]] = data["branches"]
        self.transitions: List[Dict[str, Any]] = data["transitions"]
        self.bifurcations: List[Dict[str, Any]] = data["bifurcations"]
        self.cuts: List[Dict[str, Any]] = data.get("cuts", [])
        self.cascades: List[Dict[str, Any]] = data.get("cascades", [])

    def branch_arrays(self, branch: int) -> Dict[str, np.ndarray]:
        """Branch ``branch``'s points as arrays: the parameter, ``start_Wt``,
        ``start_x``, ``eigenvalues`` (``n × 2`` complex), ``stable``, and the
        amplitudes ``max_abs_x``, ``max_abs_v`` (the largest ``|x|``, ``|v|``
        over the cycle; ``nan`` where not evaluated)."""
        pts = self.branches[branch]["points"]
        return {
            self.param: np.array([p[self.param] for p in pts], dtype=float),
            "start_Wt": np.array([p["start_Wt"] for p in pts], dtype=float),
            "start_x": np.array([p["start_x"] for p in pts], dtype=float),
            "eigenvalues": np.array([_complex(p["eigenvalues"]) for p in pts]).reshape(len(pts), -1),
            "stable": np.array([p["stable"] for p in pts], dtype=bool),
            "max_abs_x": _floats([p.get("max_abs_x") for p in pts]),
            "max_abs_v": _floats([p.get("max_abs_v") for p in pts]),
        }

    def to_pandas(self) -> Any:
        """One row per motion at each grid value: the parameter,
        ``structure``, ``N``, ``start_Wt``, ``start_x``, ``stable``,
        ``lambda_max`` (the largest ``|λ|``), and the amplitudes
        ``max_abs_x``, ``max_abs_v`` (the largest ``|x|``, ``|v|`` over the
        cycle): the frequency response, ``df.plot.scatter(param, "max_abs_x")``."""
        rows = []
        for p in self.points:
            for m in p["motions"]:
                lam = _complex(m.get("eigenvalues"))
                rows.append(
                    {
                        self.param: p[self.param],
                        "structure": m.get("structure"),
                        "N": m.get("N"),
                        "start_Wt": m.get("start_Wt"),
                        "start_x": m.get("start_x"),
                        "stable": m.get("stable"),
                        "lambda_max": float(np.abs(lam).max()) if lam.size else np.nan,
                        "max_abs_x": _float(m.get("max_abs_x")),
                        "max_abs_v": _float(m.get("max_abs_v")),
                    }
                )
        return _pandas().DataFrame(rows)

    def __repr__(self) -> str:
        return (
            f"Sweep({self.param}: {len(self.points)} values, {len(self.branches)} branches, "
            f"{len(self.transitions)} transitions, {len(self.bifurcations)} bifurcations)"
        )


class OrbitDiagram(Result):
    """The brute-force bifurcation diagram (``stickslip orbit-diagram
    --json``): at each parameter value, the stroboscopic samples ``x``, ``v``
    at ``W t = 0 mod 2π`` after the transient, swept ``up`` and ``down``
    (each value starting from the previous one's final state, so hysteresis
    shows), the largest Lyapunov exponent per unit time (``nan`` where not
    computed or where a stick collapses the map, ``null`` in the JSON), and
    the sweep's periodic ``branches`` at the section."""

    def __init__(self, data: Dict[str, Any], notes: List[str]) -> None:
        super().__init__(data)
        self.notes = list(notes)
        self.param: str = data["param"]
        self.up: List[Dict[str, Any]] = data["up"]
        self.down: List[Dict[str, Any]] = data["down"]
        self.branches: List[Dict[str, Any]] = data["branches"]
        self.values = np.array([c["value"] for c in self.up], dtype=float)

    def samples(self, direction: str = "up") -> Dict[str, np.ndarray]:
        """The samples of one sweep direction as flat arrays for a scatter
        plot: the parameter, ``x``, ``v`` (one entry per sample)."""
        cols = {"up": self.up, "down": self.down}[direction]
        par = np.concatenate([np.full(len(c["x"]), c["value"]) for c in cols]) if cols else np.zeros(0)
        x = np.concatenate([np.asarray(c["x"], dtype=float) for c in cols]) if cols else np.zeros(0)
        v = np.concatenate([np.asarray(c["v"], dtype=float) for c in cols]) if cols else np.zeros(0)
        return {self.param: par, "x": x, "v": v}

    def to_pandas(self) -> Any:
        """One row per stroboscopic sample: ``direction`` (``up``, ``down``),
        the parameter, ``x``, ``v``, and the value's largest ``exponent``
        (NaN where none)."""
        frames = {}
        for direction in ("up", "down"):
            cols = self.up if direction == "up" else self.down
            counts = [len(c["x"]) for c in cols]
            s = self.samples(direction)
            frames[direction] = {
                "direction": [direction] * len(s["x"]),
                self.param: s[self.param],
                "x": s["x"],
                "v": s["v"],
                "exponent": np.repeat(self.exponents(direction), counts) if cols else np.zeros(0),
            }
        pd = _pandas()
        return pd.concat([pd.DataFrame(f) for f in frames.values()], ignore_index=True)

    def exponents(self, direction: str = "up") -> np.ndarray:
        """The largest exponent at each value of one direction (``nan`` where none)."""
        cols = {"up": self.up, "down": self.down}[direction]
        return np.array([np.nan if c["exponent"] is None else c["exponent"] for c in cols], dtype=float)

    def __repr__(self) -> str:
        return f"OrbitDiagram({self.param}: {len(self.up)} values, {len(self.branches)} branches)"
