"""Result objects of the analyses over two parameters and over starts:
``Map``, ``Curves``, ``Lyapunov``, ``Basins`` (numpy arrays, ``to_dict()``,
``to_pandas()`` for the tabular ones)."""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from ._results import Result, _pandas


def _number(x: Any) -> float:
    """A JSON number, or ``"-inf"``/``"inf"``/``"nan"`` (JSON has no infinity)."""
    return float(x)


class Map(Result):
    """A map over two parameters (``stickslip map``): which motions exist at
    each point of the grid.

    ``x`` and ``y`` are the axes' values (numpy), ``x_name``/``y_name`` their
    parameters. The 2-d arrays are indexed ``[iy, ix]`` (rows are ``y``), so
    that ``plt.pcolormesh(m.x, m.y, m.ids)`` draws the map:

    - ``labels``: each point's class (``PointResult::label``: its motions
      joined by ``" + "``, or why none was found: ``invalid``, ``unsettled``,
      ``chaotic``, ...);
    - ``motions``: each point's motions, a tuple of names (``P_{...}`` with
      ``^N`` for a period of ``N > 1`` forcing periods, or ``NM``);
    - ``status``: ``ok``, ``invalid: ...``, or the starts that did not settle;
    - ``ids``: the position of each point's label in ``summary``.

    ``summary`` counts the points of each label, most frequent first.

    ``to_dict()``: ``{"model", "x", "y"`` (each ``{"name", "from", "to",
    "count"}``), ``"base"`` (the other parameters), ``"method"``,
    ``"complete"``, ``"computed"``, ``"already_done"``, ``"labels"`` (``[{"label",
    "points"}]``, as ``summary``), ``"file"`` (the map file, ``None`` for a
    temporary one), ``"points"}``: one record per grid point in index order
    (``index = iy * nx + ix``), ``{"index", <x name>, <y name>, "status",
    "motions"}``, the same content as the lines of the CSV file
    (``motions`` a list where the file joins them by ``;``).
    """

    def __init__(self, data: Dict[str, Any], labels: Sequence[str]) -> None:
        super().__init__(data)
        self.x_name: str = data["x"]["name"]
        self.y_name: str = data["y"]["name"]
        nx, ny = int(data["x"]["count"]), int(data["y"]["count"])
        points = data["points"]
        labels = list(labels)
        if len(points) != nx * ny or len(labels) != nx * ny or any(p["index"] != k for k, p in enumerate(points)):
            from .errors import InputError

            raise InputError(f"the map file holds {len(points)} of {nx * ny} points")
        self.x = np.array([p[self.x_name] for p in points[:nx]], dtype=float)
        self.y = np.array([points[iy * nx][self.y_name] for iy in range(ny)], dtype=float)
        self.summary: Dict[str, int] = {e["label"]: int(e["points"]) for e in data["labels"]}
        position = {label: k for k, label in enumerate(self.summary)}
        self.labels = np.array(labels, dtype=str).reshape(ny, nx)
        self.ids = np.array([position[s] for s in labels], dtype=np.int64).reshape(ny, nx)
        self.status = np.array([p["status"] for p in points], dtype=str).reshape(ny, nx)
        motions = np.empty(nx * ny, dtype=object)
        for k, p in enumerate(points):
            motions[k] = tuple(p["motions"])
        self.motions = motions.reshape(ny, nx)

    @property
    def shape(self) -> tuple:
        """``(ny, nx)``: the shape of the 2-d arrays."""
        return self.labels.shape

    def to_pandas(self) -> Any:
        """One row per grid point: ``index``, the two parameters, ``label``,
        ``status``, ``motions`` (joined by ``;`` as in the CSV)."""
        pts = self._data["points"]
        return _pandas().DataFrame(
            {
                "index": [p["index"] for p in pts],
                self.x_name: [p[self.x_name] for p in pts],
                self.y_name: [p[self.y_name] for p in pts],
                "label": self.labels.ravel(),
                "status": [p["status"] for p in pts],
                "motions": [";".join(p["motions"]) for p in pts],
            }
        )

    def __repr__(self) -> str:
        ny, nx = self.shape
        return f"Map({self.x_name} × {self.y_name}: {nx} × {ny} points, {len(self.summary)} labels)"


class Curves(Result):
    """Transition curves over a box of two parameters (``stickslip curves``).

    ``x_name``/``y_name`` name the parameters; ``curves`` is the list of
    curves as in the CLI's JSON (``kind``, ``boundary``, ``structure``,
    ``from``, ``to``, ``points``, ``at``), except that each curve's
    ``points`` and ``at`` are ``n × 2`` numpy arrays of ``(x, y)``;
    ``codim2`` lists the codimension-two points; ``failed_starts`` the
    located transitions whose curve could not be traced (``kind``,
    ``boundary``, ``structure``, the two parameters, ``why``): curves the
    run is missing. ``to_dict()`` is exactly ``stickslip curves --json``.
    """

    def __init__(self, data: Dict[str, Any]) -> None:
        super().__init__(data)
        self.x_name: str = data["x"]
        self.y_name: str = data["y"]
        self.curves: List[Dict[str, Any]] = []
        for c in data["curves"]:
            c = dict(c)
            c["points"] = np.asarray(c["points"], dtype=float).reshape(-1, 2)
            c["at"] = np.asarray(c["at"], dtype=float).reshape(-1, 2)
            self.curves.append(c)
        self.codim2: List[Dict[str, Any]] = data["codim2"]
        self.failed_starts: List[Dict[str, Any]] = data["failed_starts"]

    def __len__(self) -> int:
        return len(self.curves)

    def to_pandas(self) -> Any:
        """One row per curve: ``kind``, ``boundary``, ``structure``, how it
        ends (``from``, ``to``: ``box_edge``, ``codim2``, ..., or ``closed``),
        and its number of points."""
        end = lambda e: "closed" if e is None else e["end"]  # noqa: E731
        return _pandas().DataFrame(
            [
                {
                    "kind": c["kind"],
                    "boundary": c["boundary"],
                    "structure": c["structure"],
                    "from": end(c["from"]),
                    "to": end(c["to"]),
                    "points": len(c["points"]),
                }
                for c in self.curves
            ]
        )

    def __repr__(self) -> str:
        return f"Curves({self.x_name} × {self.y_name}: {len(self.curves)} curves, {len(self.codim2)} codim-2 points)"


class Lyapunov(Result):
    """The Lyapunov spectrum of the stroboscopic map along a simulated
    trajectory (``stickslip lyapunov``).

    ``exponents`` (per unit time) and ``per_period`` (per forcing period)
    are numpy arrays, largest first, with ``-inf`` where a stick collapses a
    direction; ``error`` is the standard error of the block means;
    ``attractor`` is ``periodic``, ``chaotic``, ``quasi_periodic``, ``NM``,
    ``stick`` or ``long_cycle``; ``structure`` and ``N`` name the periodic
    motion (else ``None``); ``end`` is the final state ``(x, v, Wt)``.
    ``to_dict()`` is exactly ``stickslip lyapunov --json`` (with ``"-inf"``
    strings).
    """

    def __init__(self, data: Dict[str, Any]) -> None:
        super().__init__(data)
        self.exponents = np.array([_number(e) for e in data["exponents"]], dtype=float)
        self.per_period = np.array([_number(e) for e in data["per_period"]], dtype=float)
        self.error: float = _number(data["error"])
        self.attractor: str = data["attractor"]
        self.structure: Optional[str] = data.get("structure")
        self.N: Optional[int] = data.get("periods_per_cycle")
        self.end = np.array(data["end"], dtype=float)

    def to_pandas(self) -> Any:
        """The spectrum, one row per exponent (largest first): ``exponent``
        (per unit time) and ``per_period`` (per forcing period)."""
        return _pandas().DataFrame({"exponent": self.exponents, "per_period": self.per_period})

    def __repr__(self) -> str:
        what = self.attractor if self.structure is None else f"{self.attractor} {self.structure}"
        return f"Lyapunov({what}, exponents = {self.exponents.tolist()})"


class Basins(Result):
    """Basins of attraction and basin stability (``stickslip basins``).

    ``x`` and ``v`` are the grid's start displacements and velocities;
    ``ids`` is the 2-d array ``[iv, ix]`` of the attractor each grid start
    reaches, as its position in ``attractors`` (so
    ``plt.pcolormesh(b.x, b.v, b.ids)`` draws the basins); ``exponents`` the
    same grid's largest Lyapunov exponents (NaN where none was computed: the
    start settled). ``sample_starts`` (``S × 2``: ``x, v``), ``sample_ids``
    and ``sample_exponents`` are the random starts of the basin stability.

    ``attractors`` lists each attractor (``name``, grid ``points`` and
    ``fraction``, random ``samples`` and ``stability`` with its 95 % Wilson
    ``interval``, mean ``exponent`` where computed, an ``example`` start),
    largest basin first; ``names``, ``fractions``, ``stability`` and
    ``intervals`` (``k × 2``) are the same as arrays. ``to_dict()`` is
    exactly ``stickslip basins --json`` (``"file"`` is ``None`` for a
    temporary file).
    """

    def __init__(
        self,
        data: Dict[str, Any],
        x: Sequence[float],
        v: Sequence[float],
        ids: Sequence[int],
        exponents: Sequence[float],
    ) -> None:
        super().__init__(data)
        nx, nv = int(data["x"]["count"]), int(data["v"]["count"])
        grid = nx * nv
        xs = np.asarray(x, dtype=float)
        vs = np.asarray(v, dtype=float)
        all_ids = np.asarray(ids, dtype=np.int64)
        all_exp = np.asarray(exponents, dtype=float)
        self.x = xs[:nx].copy()
        self.v = vs[:grid:nx].copy()
        self.ids = all_ids[:grid].reshape(nv, nx)
        self.exponents = all_exp[:grid].reshape(nv, nx)
        self.sample_starts = np.stack([xs[grid:], vs[grid:]], axis=1).reshape(-1, 2)
        self.sample_ids = all_ids[grid:]
        self.sample_exponents = all_exp[grid:]
        self.phase: float = data["phase"]
        self.attractors: List[Dict[str, Any]] = data["attractors"]
        self.names: List[str] = [a["name"] for a in self.attractors]
        self.fractions = np.array([a["fraction"] for a in self.attractors], dtype=float)
        self.stability = np.array([a["stability"] for a in self.attractors], dtype=float)
        self.intervals = np.array([a["interval"] for a in self.attractors], dtype=float).reshape(-1, 2)

    def to_pandas(self) -> Any:
        """The attractor table, one row per attractor: ``name``, ``points``,
        ``fraction``, ``samples``, ``stability``, ``low``, ``high`` (the 95 %
        interval), ``exponent`` (NaN where none), ``example_x``, ``example_v``."""
        return _pandas().DataFrame(
            [
                {
                    "name": a["name"],
                    "points": a["points"],
                    "fraction": a["fraction"],
                    "samples": a["samples"],
                    "stability": a["stability"],
                    "low": a["interval"][0],
                    "high": a["interval"][1],
                    "exponent": a.get("exponent", np.nan),
                    "example_x": a["example"][0],
                    "example_v": a["example"][1],
                }
                for a in self.attractors
            ]
        )

    def __repr__(self) -> str:
        nv, nx = self.ids.shape
        return f"Basins({nx} × {nv} starts at Wt = {self.phase}, {len(self.attractors)} attractors)"
