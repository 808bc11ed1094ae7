"""The package's shape, as a notebook user expects it: numpy arrays where a notebook
plots, ``to_dict()`` on every result and ``to_pandas()`` on the tabular ones,
type stubs that match the extension, long calls that release the GIL."""

from __future__ import annotations

import ast
import json
import pathlib
import threading
import time
from typing import Any, Dict, List, Tuple

import numpy as np
import pytest

import stickslip
from conftest import close
from stickslip import _native

BASIN_SET = {"W": 3.94826, "Q0": 70.0}
BASIN_X = (0.99, 1.005, 6)
BASIN_V = (1.335, 1.36, 5)


@pytest.fixture(scope="module")
def paper() -> stickslip.Model:
    return stickslip.Model("paper")


# ---------------------------------------------------------------- arrays


def test_history_columns_are_numpy_arrays_and_to_dict_lists(paper):
    h = paper.simulate(W=5, Q0=70).history(periods=2, samples=50)
    for c in stickslip.History.COLUMNS:
        a = getattr(h, c)
        assert isinstance(a, np.ndarray) and a.ndim == 1 and len(a) == len(h)
        assert a.dtype == (np.int64 if c == "domain" else np.float64)
        assert a.flags.writeable and a.flags.c_contiguous
    d = h.to_dict()
    assert list(d) == list(stickslip.History.COLUMNS)
    # Plain Python numbers, as the CLI's JSON has them.
    assert all(type(u) is float for c in stickslip.History.COLUMNS[:-1] for u in d[c])
    assert all(type(u) is int for u in d["domain"])
    assert d == json.loads(json.dumps(d))
    assert d["x"] == h.x.tolist() and d["domain"] == h.domain.tolist()
    # A deep copy: changing it changes nothing.
    d["x"][0] = 1e9
    assert h.to_dict()["x"][0] == h.x[0] != 1e9
    assert h["t"] == h.t.tolist()


def test_motion_arrays(paper):
    m = paper.simulate(W=5, Q0=70)
    assert isinstance(m.points, np.ndarray) and m.points.dtype == np.float64
    assert m.points.shape == (len(m.mappings), 3)
    assert isinstance(m.eigenvalues, np.ndarray) and m.eigenvalues.dtype == np.complex128
    assert m.eigenvalues.shape == (len(m.to_dict()["eigenvalues"]),)
    want = [complex(re, im) for re, im in m.to_dict()["eigenvalues"]]
    assert m.eigenvalues.tolist() == want
    # No motion to speak of: empty arrays of the same types.
    nm = stickslip.Model("coulomb").simulate(W=0.3)
    assert nm.eigenvalues.dtype == np.complex128 and nm.points.shape[1] == 3


def test_basins_arrays(paper):
    b = paper.basins(x=BASIN_X, y=BASIN_V, samples=20, progress=False, **BASIN_SET)
    nx, nv = BASIN_X[2], BASIN_V[2]
    assert b.ids.shape == b.exponents.shape == (nv, nx)
    assert b.ids.dtype == np.int64 and b.exponents.dtype == np.float64
    assert b.x.shape == (nx,) and b.v.shape == (nv,)
    assert b.sample_starts.shape == (20, 2) and b.sample_ids.shape == (20,)
    assert b.ids.min() >= 0 and b.ids.max() < len(b.attractors)


# ---------------------------------------------------------------- to_dict, to_pandas


def results(paper) -> Dict[str, Any]:
    """One of each result, small."""
    m = paper.simulate(W=5, Q0=70)
    return {
        "Description": paper.describe(W=5),
        "Motion": m,
        "History": m.history(samples=40),
        "Sweep": paper.sweep("W", np.linspace(3.0, 4.0, 6), Q0=70),
        "OrbitDiagram": stickslip.Model("stribeck8").orbit_diagram(
            "W", 2.2, 2.45, 3, transient=20, periods=4, lyapunov=20, branches=False, Q0=3
        ),
        "Map": paper.map(x=("W", 0.2, 8, 3), y=("Q0", 0, 180, 2), progress=False),
        "Curves": paper.curves(x=("W", 3.0, 4.0), y=("Q0", 65, 75), count=10, spread=0),
        "Lyapunov": paper.lyapunov(transient=50, periods=50, W=5, Q0=70),
        "Equilibria": stickslip.Model("stribeck").equilibria(along=("V", 0.2, 3.0, 3), Q0=0),
        "LawMotion": stickslip.Model("stribeck").simulate(),
        "LawSweep": stickslip.Model("stribeck").sweep("V", [0.5, 1.5], Q0=0),
        "Basins": paper.basins(x=BASIN_X, y=BASIN_V, samples=10, progress=False, **BASIN_SET),
    }


def test_every_result_has_to_dict_and_to_pandas(paper):
    pd = pytest.importorskip("pandas")
    made = results(paper)
    # Every result class the package exports is here.
    exported = {n for n in stickslip.__all__ if isinstance(getattr(stickslip, n), type)}
    classes = {n for n in exported if issubclass(getattr(stickslip, n), stickslip.Result)} - {"Result"}
    assert classes == set(made)
    for name, r in made.items():
        assert type(r).__name__ == name
        d = r.to_dict()
        assert isinstance(d, dict) and d
        json.dumps(d)  # the CLI's JSON: serializable as it is
        df = r.to_pandas()
        assert isinstance(df, pd.DataFrame) and len(df) > 0, name
    # A few tables, checked against their arrays.
    od = made["OrbitDiagram"]
    df = od.to_pandas()
    assert len(df) == 2 * 3 * 4 and set(df["direction"]) == {"up", "down"}
    up = df[df["direction"] == "up"]
    assert up["x"].tolist() == od.samples("up")["x"].tolist()
    ly = made["Lyapunov"].to_pandas()
    assert ly["exponent"].tolist() == made["Lyapunov"].exponents.tolist()
    desc = made["Description"]
    assert len(desc.to_pandas("boundaries")) == len(desc["boundaries"])
    with pytest.raises(stickslip.InputError):
        desc.to_pandas("nope")


# ---------------------------------------------------------------- stubs


def stub_functions() -> Dict[str, List[Tuple[str, Any]]]:
    """``_native.pyi``'s functions (and ``Trajectory``'s methods), each as
    ``[(parameter, default)]`` (``...`` marks no default)."""
    path = pathlib.Path(stickslip.__file__).with_name("_native.pyi")
    tree = ast.parse(path.read_text())
    out: Dict[str, List[Tuple[str, Any]]] = {}

    def params(f: ast.FunctionDef) -> List[Tuple[str, Any]]:
        args = [a.arg for a in f.args.args]
        defaults = [ast.literal_eval(d) for d in f.args.defaults]
        full = [NotImplemented] * (len(args) - len(defaults)) + defaults
        return [(a.rstrip("_") if a != "self" else "$self", d) for a, d in zip(args, full)]

    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out[node.name] = params(node)
        elif isinstance(node, ast.ClassDef):
            for f in node.body:
                if isinstance(f, ast.FunctionDef):
                    out[f"{node.name}.{f.name}"] = params(f)
    return out


def text_signature(f: Any) -> List[Tuple[str, Any]]:
    """PyO3's ``__text_signature__`` as ``[(parameter, default)]``."""
    sig = f.__text_signature__
    assert sig and sig[0] == "(" and sig[-1] == ")", sig
    out = []
    for part in filter(None, (p.strip() for p in sig[1:-1].split(","))):
        name, _, default = part.partition("=")
        value = NotImplemented if not default else (... if default == "..." else ast.literal_eval(default))
        out.append((name.rstrip("_"), value))
    return out


def test_stubs_match_the_extension():
    stubs = stub_functions()
    native = {n for n in dir(_native) if not n.startswith("_") and callable(getattr(_native, n))}
    native.discard("Trajectory")
    native |= {"Trajectory.history", "Trajectory.title"}
    assert set(stubs) == native
    for name in sorted(native):
        obj = _native
        for part in name.split("."):
            obj = getattr(obj, part)
        assert stubs[name] == text_signature(obj), name


def test_stub_of_the_package_is_shipped():
    root = pathlib.Path(stickslip.__file__).parent
    assert (root / "py.typed").is_file() and (root / "_native.pyi").is_file()


# ---------------------------------------------------------------- the GIL


def unsettled(model: str, **kwargs: Any) -> None:
    """A simulation that never settles (chaos), to its last period."""
    with pytest.raises(stickslip.UnsettledError):
        stickslip.Model(model).simulate(**kwargs)


LONG_CALLS = {
    "simulate": lambda m: unsettled("stribeck8", periods=1000, W=2.3, Q0=3),
    "sweep": lambda m: m.sweep("W", np.linspace(0.2, 9, 200), Q0=70),
    "lyapunov": lambda m: m.lyapunov(transient=0, periods=20000, W=5, Q0=70),
    "map": lambda m: m.map(x=("W", 0.2, 8, 12), y=("Q0", 0, 180, 12), progress=False),
    "basins": lambda m: m.basins(x=(-5, 5, 12), y=(-10, 10, 12), samples=100, progress=False, **BASIN_SET),
    "curves": lambda m: m.curves(x=("W", 3.0, 4.0), y=("Q0", 65, 75), count=10, spread=0),
    "orbit_diagram": lambda m: stickslip.Model("stribeck8").orbit_diagram(
        "W", 2.2, 2.45, 4, transient=200, periods=50, lyapunov=200, branches=False, Q0=3
    ),
}


@pytest.mark.parametrize("what", sorted(LONG_CALLS))
def test_long_calls_release_the_gil(paper, what):
    """Another Python thread runs while the call computes: with the GIL
    held it would wait for the whole call."""
    call = LONG_CALLS[what]
    errors: List[BaseException] = []

    def work() -> None:
        try:
            call(paper)
        except BaseException as e:  # noqa: BLE001 - reported below
            errors.append(e)

    t = threading.Thread(target=work)
    ticks = 0
    start = time.perf_counter()
    t.start()
    while t.is_alive():
        ticks += 1
        time.sleep(0.001)
    took = time.perf_counter() - start
    t.join()
    assert not errors, errors
    if took < 0.05:
        pytest.skip(f"{what} took {took * 1e3:.1f} ms: too short to tell")
    # About one tick a millisecond while the call runs; with the GIL held, none.
    assert ticks >= max(5, int(took * 1000 / 10)), (ticks, took)


def test_unforced_motions_carry_their_stability():
    """The undamped Coulomb belt oscillator's stick-slip cycle (closed form:
    stick 2 (x_r - x_k) / V, slip (pi + 2 atan(V / (x_r - x_k))) with c = 1),
    and steady sliding of a damped one."""
    import math

    coulomb = stickslip.Model("coulomb")
    cycle = coulomb.simulate((0.0, 0.5, 0.0), Q0=0, d=0, V=0.5)
    assert cycle.kind == "autonomous_cycle"
    assert abs(cycle.stick_time - 0.4) < 1e-10
    assert abs(cycle.period - (0.4 + math.pi + 2 * math.atan(0.5 / 0.1))) < 1e-10
    assert cycle.multiplier is not None and abs(cycle.multiplier) < 1e-12
    assert cycle.stable is True
    rest = coulomb.simulate(Q0=0, d=0.1, V=0.5)
    assert rest.kind == "NM" and rest.stable is True
    assert abs(rest.steady_sliding["x"] - 0.3) < 1e-15
    assert rest.steady_sliding["verdict"] == "stable"


def test_simulate_takes_a_smooth_law_itself():
    """The Stribeck law integrated: unforced below its Hopf point it settles
    on a stick-slip cycle (superstable: multiplier 0), above it in the
    bistable window to steady sliding from rest; forced, on a periodic
    motion with stick. The same numbers as `stickslip simulate --json`."""
    law = stickslip.Model("stribeck")
    cycle = law.simulate(Q0=0, V=0.5)
    assert cycle.kind == "cycle" and cycle.stable
    assert cycle.stick > 0 and cycle.period > cycle.stick and cycle.multiplier == 0.0
    events = cycle["cycle"]["events"]
    assert [e["after"] for e in events].count("stick") == 1
    rest = law.simulate(Q0=0, V=3.0)
    assert rest.kind == "steady_sliding" and rest.stable
    forced = law.simulate()
    assert forced.kind == "periodic" and forced["sticks"] and forced["periods"] == 1
    with pytest.raises(stickslip.InputError):
        law.simulate(periods=0)


def test_a_smooth_law_is_swept_as_the_cli_does(cli):
    """The Stribeck law itself along V: the CLI's JSON; below the Hopf point
    only the stable stick-slip cycle, above it steady sliding stable with
    the unstable slip cycle inside the stick-slip cycle; the Hopf point at
    its closed form. A forced law is an input error, as is a grid that does
    not increase."""
    import math

    law = stickslip.Model("stribeck")
    s = law.sweep("V", np.linspace(0.5, 2.5, 5), Q0=0)
    assert isinstance(s, stickslip.LawSweep)
    want = cli.json("sweep", "--model", "stribeck", "--param", "V=0.5:2.5:5", "--set", "Q0=0")
    close(s.to_dict(), want)
    p = {k: v.default for k, v in law.params.items()}
    closed = -p["vs"] * math.log((2 * p["d"] + p["sigma"]) * p["vs"] / ((p["mus"] - p["muk"]) * p["g"]))
    assert len(s.changes) == 1 and abs(s.changes[0]["at"] - closed) <= 1e-9 * closed
    for point in s.points:
        kinds = sorted("stick_slip" if c["stick"] > 0 else "slip" for c in point["cycles"])
        stable_rest = point["equilibrium"]["verdict"] == "stable"
        assert stable_rest == (point["value"] > closed)
        assert kinds == (["slip", "stick_slip"] if stable_rest else ["stick_slip"])
        if stable_rest:
            slip, stick_slip = sorted(point["cycles"], key=lambda c: c["x"])
            assert slip["verdict"] == "unstable" and stick_slip["verdict"] == "stable"
    frame = s.to_pandas() if _has_pandas() else None
    if frame is not None:
        assert len(frame) == 5 + sum(len(p["cycles"]) for p in s.points)
    with pytest.raises(stickslip.InputError, match="forcing"):
        law.sweep("V", [0.5, 1.0])
    with pytest.raises(stickslip.InputError, match="increasing"):
        law.sweep("V", [1.0, 0.5], Q0=0)


def _has_pandas() -> bool:
    try:
        import pandas  # noqa: F401
    except ImportError:
        return False
    return True


def test_equilibria_of_a_smooth_law_locate_its_hopf_point():
    """Steady sliding of the Stribeck law itself (no pieces) loses stability
    where 2 d + f'(0) = 0: V* = -vs ln((2 d + sigma) vs / ((mus - muk) g))."""
    import math

    law = stickslip.Model("stribeck")
    scan = law.equilibria(along=("V", 0.2, 3.0, 15), Q0=0)
    p = {k: v.default for k, v in law.params.items()}
    closed = -p["vs"] * math.log((2 * p["d"] + p["sigma"]) * p["vs"] / ((p["mus"] - p["muk"]) * p["g"]))
    assert len(scan.changes) == 1
    assert abs(scan.changes[0]["at"] - closed) <= 1e-9 * closed
    assert scan.values.shape == (15,) and np.all(np.isfinite(scan.x))
    one = law.equilibria(Q0=0, V=2.0)
    assert one.points[0]["equilibrium"]["verdict"] == "stable"
    forced = law.equilibria(V=2.0)
    assert forced.points[0]["equilibrium"] is None and "forc" in forced.points[0]["none"]
    with pytest.raises(stickslip.InputError):
        law.equilibria(along=("V", 0.2, 3.0, 0), Q0=0)
