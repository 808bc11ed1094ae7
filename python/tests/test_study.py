"""The analyses over two parameters and over starts (map, curves, lyapunov,
basins) against the command-line tool: the same numbers (bit for bit), the
same files, the same errors as Python exceptions, and the progress bar.

The CLI is the ``cli`` fixture of ``conftest.py`` (``STICKSLIP_CLI``, else
the repository's ``target/release/stickslip``).
"""

from __future__ import annotations

import csv
import json
import tempfile
from pathlib import Path
from typing import Any, Dict, List

import numpy as np
import pytest

import stickslip
from stickslip import errors

# The README's Fig. 11 range, coarsely.
MAP_X = ("W", 0.2, 8.0, 6)
MAP_Y = ("Q0", 0.0, 180.0, 5)
# The README's basin window of three coexisting motions, coarsely.
BASIN_SET = {"W": 3.94826, "Q0": 70.0}
BASIN_X = (0.99, 1.005, 12)
BASIN_V = (1.335, 1.36, 10)


def ok(cli, *args: str) -> str:
    """The CLI's stdout; it must succeed."""
    run = cli.run(*args)
    assert run.returncode == 0, run.stderr
    return run.stdout


def spec(axis: tuple) -> str:
    name, lo, hi, n = axis
    return f"{name}={lo}:{hi}:{n}"


def grid_value(lo: float, hi: float, n: int, i: int) -> float:
    """``GridAxis::value``, as the library computes it."""
    if n <= 1 or i == 0:
        return lo
    if i + 1 == n:
        return hi
    return lo + (hi - lo) * i / (n - 1)


def read_records(path: Path) -> List[List[str]]:
    """The data lines of a map or basin file (after the two header lines)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0][0].startswith("# stickslip")
    return rows[2:]


@pytest.fixture(scope="module")
def paper() -> stickslip.Model:
    return stickslip.Model("paper")


# ---------------------------------------------------------------- map


@pytest.mark.parametrize("method", ["continuation", "simulation"])
def test_map_agrees_with_the_cli(cli, paper, tmp_path, method):
    theirs = tmp_path / "cli.csv"
    ok(cli, "map", "--x", spec(MAP_X), "--y", spec(MAP_Y), "--method", method, "--out", str(theirs))
    ours = tmp_path / "py.csv"
    m = paper.map(x=MAP_X, y=MAP_Y, method=method, out=ours, progress=False)
    # The same file, byte for byte.
    assert ours.read_bytes() == theirs.read_bytes()
    d = m.to_dict()
    assert d["file"] == str(ours) and d["complete"] and d["method"] == method
    assert d["x"] == {"name": "W", "from": 0.2, "to": 8.0, "count": 6}
    rows = read_records(theirs)
    nx, ny = MAP_X[3], MAP_Y[3]
    assert m.shape == (ny, nx) and len(d["points"]) == len(rows) == nx * ny
    counts: Dict[str, int] = {}
    for p, (index, w, q0, status, motions) in zip(d["points"], rows):
        k = int(index)
        ix, iy = k % nx, k // nx
        assert p["index"] == k
        # Bit for bit: the CSV prints shortest round-trip numbers.
        assert p["W"] == float(w) == m.x[ix] == grid_value(0.2, 8.0, nx, ix)
        assert p["Q0"] == float(q0) == m.y[iy] == grid_value(0.0, 180.0, ny, iy)
        assert p["status"] == status == m.status[iy, ix]
        names = motions.split(";") if motions else []
        assert p["motions"] == names and m.motions[iy, ix] == tuple(names)
        assert status == "ok" and names  # every point of this range settles
        label = " + ".join(names)
        assert m.labels[iy, ix] == label
        assert list(m.summary)[m.ids[iy, ix]] == label
        counts[label] = counts.get(label, 0) + 1
    assert m.summary == counts
    assert list(m.summary.values()) == sorted(counts.values(), reverse=True)
    # The CLI's summary lines: count, label.
    printed = {
        line.split(None, 1)[1]: int(line.split(None, 1)[0])
        for line in cli_summary(cli, theirs, method).splitlines()[1:]
    }
    assert printed == counts
    df = m.to_pandas()
    assert list(df["label"]) == list(m.labels.ravel()) and list(df["W"]) == [p["W"] for p in d["points"]]


def cli_summary(cli, path: Path, method: str) -> str:
    """``stickslip map --resume`` of a finished map prints its summary again."""
    return ok(
        cli,
        "map", "--x", spec(MAP_X), "--y", spec(MAP_Y), "--method", method, "--out", str(path), "--resume"
    )


def test_map_in_a_temporary_file_leaves_nothing(paper, tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    m = paper.map(x=MAP_X, y=MAP_Y, progress=False)
    assert list(tmp_path.iterdir()) == []
    kept = paper.map(x=MAP_X, y=MAP_Y, out=tmp_path / "kept.csv", progress=False)
    d, e = m.to_dict(), kept.to_dict()
    assert d.pop("file") is None and e.pop("file") == str(tmp_path / "kept.csv")
    assert d == e


def test_map_resume(paper, tmp_path):
    out = tmp_path / "m.csv"
    first = paper.map(x=MAP_X, y=MAP_Y, out=out, progress=False)
    whole = out.read_bytes()
    # A run killed after some points: the header and the first records, a partial line.
    lines = whole.split(b"\n")
    out.write_bytes(b"\n".join(lines[:9]) + b"\n" + lines[9][:5])
    again = paper.map(x=MAP_X, y=MAP_Y, out=out, resume=True, progress=False)
    assert out.read_bytes() == whole
    assert again.to_dict()["already_done"] == 7 and again.to_dict()["computed"] == 23
    assert np.array_equal(again.labels, first.labels)


def test_map_bad_inputs(cli, paper, tmp_path):
    with pytest.raises(errors.ParamError) as e:
        paper.map(x=("Z", 0, 1, 3), y=MAP_Y, out=tmp_path / "a.csv", progress=False)
    assert str(e.value) == cli.error("map", "--x", "Z=0:1:3", "--y", spec(MAP_Y), "--out", str(tmp_path / "b.csv"))
    with pytest.raises(errors.InputError, match="must be a positive integer"):
        paper.map(x=("W", 0.2, 8, 0), y=MAP_Y, progress=False)
    with pytest.raises(errors.InputError, match="not a finite number"):
        paper.map(x=("W", 0.2, float("inf"), 3), y=MAP_Y, progress=False)
    with pytest.raises(errors.InputError, match="both axes vary"):
        paper.map(x=MAP_X, y=("W", 1, 2, 3), progress=False)
    with pytest.raises(errors.InputError, match="expected"):
        paper.map(x=("W", 0.2, 8), y=MAP_Y, progress=False)
    with pytest.raises(errors.InputError, match="method"):
        paper.map(x=MAP_X, y=MAP_Y, method="guess", progress=False)
    with pytest.raises(errors.ParamError):
        paper.map(x=MAP_X, y=MAP_Y, m=-1, progress=False)
    out = tmp_path / "exists.csv"
    out.write_text("something\n")
    with pytest.raises(errors.InputError, match="resume=True"):
        paper.map(x=MAP_X, y=MAP_Y, out=out, progress=False)
    with pytest.raises(errors.InputError, match="not a stickslip map file"):
        paper.map(x=MAP_X, y=MAP_Y, out=out, resume=True, progress=False)
    with pytest.raises(errors.ModelError):
        stickslip.Model("no_such_model")


# ---------------------------------------------------------------- curves


def test_curves_agree_with_the_cli(cli, paper):
    theirs = json.loads(
        ok(
            cli,
            "curves", "--x", "W=3:5", "--y", "Q0=60:80", "--seed", "Q0=70", "--at", "W=4",
            "--count", "30", "--spread", "0", "--json",
        )
    )
    c = paper.curves(x=("W", 3, 5), y=("Q0", 60, 80), seed={"Q0": 70}, at=[("W", 4)], count=30, spread=0)
    assert c.to_dict() == theirs
    assert len(c) == len(theirs["curves"]) > 0 and c.x_name == "W" and c.y_name == "Q0"
    assert c.failed_starts == theirs["failed_starts"]
    for ours, their in zip(c.curves, theirs["curves"]):
        assert ours["points"].shape == (len(their["points"]), 2)
        assert np.array_equal(ours["points"], np.array(their["points"]))
        assert np.array_equal(ours["at"], np.array(their["at"]).reshape(-1, 2))
        assert ours["kind"] == their["kind"] and ours["structure"] == their["structure"]
        # Every curve ending on the box's edge ends on it.
        for end in (their["from"], their["to"]):
            if end is not None and end["end"] == "box_edge":
                assert end["W"] in (3.0, 5.0) or end["Q0"] in (60.0, 80.0)
    # At least one curve crosses W = 4, and its crossings lie on the line.
    crossings = np.concatenate([k["at"] for k in c.curves])
    assert len(crossings) > 0 and np.all(crossings[:, 0] == 4.0)
    assert len(c.to_pandas()) == len(c)


def test_curves_bad_inputs(cli, paper):
    box = dict(x=("W", 3, 5), y=("Q0", 60, 80), count=30, spread=0)
    with pytest.raises(errors.InputError) as e:
        paper.curves(**{**box, "x": ("W", 5, 3)})
    assert str(e.value) == cli.error("curves", "--x", "W=5:3", "--y", "Q0=60:80")
    with pytest.raises(errors.ParamError) as e:
        paper.curves(**{**box, "x": ("Z", 3, 5)})
    assert str(e.value) == cli.error("curves", "--x", "Z=3:5", "--y", "Q0=60:80")
    with pytest.raises(errors.InputError, match="neither"):
        paper.curves(**box, seed={"d": 0.1})
    with pytest.raises(errors.InputError, match="outside the box"):
        paper.curves(**box, at={"Q0": [70, 90]})
    with pytest.raises(errors.InputError, match="at least 2"):
        paper.curves(**{**box, "count": 1})
    with pytest.raises(errors.ParamError):
        paper.curves(**box, d=-5)
    with pytest.raises(errors.InputError) as e:
        paper.curves(**box, max_mappings=0)
    assert str(e.value) == cli.error(
        "curves", "--x", "W=3:5", "--y", "Q0=60:80", "--count", "30", "--spread", "0", "--max-mappings", "0"
    )


def test_curves_max_mappings_agrees_with_the_cli(cli, paper):
    args = ("--x", "W=3:4", "--y", "Q0=65:75", "--count", "10", "--spread", "0", "--json")
    theirs = json.loads(ok(cli, "curves", *args, "--max-mappings", "4"))
    few = paper.curves(x=("W", 3, 4), y=("Q0", 65, 75), count=10, spread=0, max_mappings=4)
    assert few.to_dict() == theirs
    assert all(len(k["structure"].split()) <= 4 for k in theirs["curves"])
    every = paper.curves(x=("W", 3, 4), y=("Q0", 65, 75), count=10, spread=0)
    assert len(every) > len(few)


def test_curves_probes_agree_with_the_cli(cli, paper):
    args = ("--x", "W=3:4", "--y", "Q0=65:75", "--count", "10", "--spread", "0", "--json")
    theirs = json.loads(ok(cli, "curves", *args, "--probes", "2"))
    probed = paper.curves(x=("W", 3, 4), y=("Q0", 65, 75), count=10, spread=0, probes=2)
    assert probed.to_dict() == theirs
    # On this box the edges' sweeps find every band the probes do, so the
    # probes are compared without them.
    box = dict(x=("W", 3, 4), y=("Q0", 65, 75), count=10, spread=0, edges=False)
    assert len(paper.curves(probes=2, **box)) > len(paper.curves(**box))
    with pytest.raises(errors.InputError, match="probes"):
        paper.curves(x=("W", 3, 4), y=("Q0", 65, 75), probes=-1)


def test_curves_partners_agree_with_the_cli(cli, paper):
    args = ("--x", "W=3:4", "--y", "Q0=65:75", "--count", "10", "--spread", "0", "--json")
    theirs = json.loads(ok(cli, "curves", *args, "--max-partners", "0"))
    box = dict(x=("W", 3, 4), y=("Q0", 65, 75), count=10, spread=0)
    off = paper.curves(max_partners=0, **box)
    assert off.to_dict() == theirs
    # Branch switching at the codimension-two points adds the bands'
    # second curves and keeps every curve the lines found.
    on = paper.curves(**box)
    assert on.to_dict() == json.loads(ok(cli, "curves", *args))
    assert len(on) > len(off)
    found = {(c["kind"], c["structure"], str(c["points"])) for c in on.to_dict()["curves"]}
    assert all((c["kind"], c["structure"], str(c["points"])) in found for c in theirs["curves"])
    with pytest.raises(errors.InputError, match="max_partners"):
        paper.curves(max_partners=-1, **box)


def test_curves_edges_agree_with_the_cli(cli, paper):
    args = ("--x", "W=3:4", "--y", "Q0=65:75", "--count", "10", "--spread", "0", "--json")
    # The edges are swept by default, on both sides.
    theirs = json.loads(ok(cli, "curves", *args))
    edged = paper.curves(x=("W", 3, 4), y=("Q0", 65, 75), count=10, spread=0)
    assert edged.to_dict() == theirs
    assert json.loads(ok(cli, "curves", *args, "--edges")) == theirs
    plain_cli = json.loads(ok(cli, "curves", *args, "--no-edges"))
    plain = paper.curves(x=("W", 3, 4), y=("Q0", 65, 75), count=10, spread=0, edges=False)
    assert plain.to_dict() == plain_cli
    assert len(plain.to_dict()["curves"]) < len(theirs["curves"])


# ---------------------------------------------------------------- lyapunov


@pytest.mark.parametrize(
    "model, params, start",
    [
        ("stribeck8", {"W": 2.38, "Q0": 3}, (0.0, 0.0, 0.0)),  # chaotic, with -inf
        ("paper", {"W": 5, "Q0": 70}, (0.5, -0.25, 1.0)),  # periodic
    ],
)
def test_lyapunov_agrees_with_the_cli(cli, model, params, start):
    sets = ",".join(f"{k}={v}" for k, v in params.items())
    frm = ",".join(str(u) for u in start)
    theirs = json.loads(
        ok(
            cli,
            "lyapunov", "--model", model, "--set", sets, f"--from={frm}",
            "--transient", "50", "--periods", "1500", "--json",
        )
    )
    ly = stickslip.Model(model).lyapunov(start=start, transient=50, periods=1500, **params)
    assert ly.to_dict() == theirs
    assert ly.attractor == theirs["attractor"] and ly.structure == theirs["structure"]
    num = lambda v: float(v)  # noqa: E731 - "-inf" strings are numbers to float()
    assert np.array_equal(ly.exponents, [num(v) for v in theirs["exponents"]])
    assert np.array_equal(ly.per_period, [num(v) for v in theirs["per_period"]])
    assert ly.error == num(theirs["error"])
    if model == "stribeck8":
        assert ly.attractor == "chaotic" and ly.exponents[0] > 0
        assert ly.exponents[1] == -np.inf and ly.per_period[1] == -np.inf
    else:
        assert ly.attractor == "periodic" and ly.N == theirs["periods_per_cycle"] == 1
        # Per forcing period = per unit time × 2π/W.
        assert np.allclose(ly.per_period, ly.exponents * 2 * np.pi / 5, rtol=1e-12, atol=0)


def test_lyapunov_bad_inputs(cli, paper):
    with pytest.raises(errors.InputError, match="at least 1"):
        paper.lyapunov(periods=0)
    with pytest.raises(errors.InputError, match="start"):
        paper.lyapunov(start=(0, float("nan"), 0))
    with pytest.raises(errors.InputError, match="integer"):
        paper.lyapunov(periods=2.5)
    with pytest.raises(errors.ParamError) as e:
        paper.lyapunov(W=-1, periods=10)
    assert str(e.value) == cli.error("lyapunov", "--set", "W=-1", "--periods", "10")
    with pytest.raises(errors.SimulationError, match="blows up") as e:
        paper.lyapunov(start=(1e308, 0, 0), transient=0, periods=10)
    assert str(e.value) == cli.error("lyapunov", "--from", "1e308,0,0", "--transient", "0", "--periods", "10")


# ---------------------------------------------------------------- basins


def basin_args(out: Path, samples: int) -> List[str]:
    sets = ",".join(f"{k}={v}" for k, v in BASIN_SET.items())
    return [
        "basins", "--set", sets, "--x", "x={}:{}:{}".format(*BASIN_X), "--y", "v={}:{}:{}".format(*BASIN_V),
        "--samples", str(samples), "--out", str(out), "--json",
    ]


def test_basins_agree_with_the_cli(cli, paper, tmp_path):
    out = tmp_path / "b.csv"
    theirs = json.loads(ok(cli, *basin_args(out, 60)))
    file = out.read_bytes()
    rows = read_records(out)
    out.unlink()
    b = paper.basins(x=BASIN_X, y=BASIN_V, samples=60, out=out, progress=False, **BASIN_SET)
    assert b.to_dict() == theirs
    assert out.read_bytes() == file
    # Three coexisting motions (the guide, "Chaos and basins").
    assert len(b.attractors) == 3 and b.names == [a["name"] for a in theirs["attractors"]]
    nx, nv = BASIN_X[2], BASIN_V[2]
    assert b.ids.shape == (nv, nx) and len(rows) == nx * nv + 60
    for index, x, v, attractor, exponent in rows:
        k = int(index)
        if k < nx * nv:
            ix, iv = k % nx, k // nx
            assert b.x[ix] == float(x) == grid_value(*BASIN_X, ix)
            assert b.v[iv] == float(v) == grid_value(*BASIN_V, iv)
            assert b.names[b.ids[iv, ix]] == attractor
            assert np.isnan(b.exponents[iv, ix]) if exponent == "" else b.exponents[iv, ix] == float(exponent)
        else:
            s = k - nx * nv
            assert tuple(b.sample_starts[s]) == (float(x), float(v))
            assert b.names[b.sample_ids[s]] == attractor
    # Fractions and stabilities are the counts' shares.
    for k, a in enumerate(b.attractors):
        assert a["points"] == np.count_nonzero(b.ids == k)
        assert b.fractions[k] == a["points"] / (nx * nv)
        assert a["samples"] == np.count_nonzero(b.sample_ids == k)
        assert b.stability[k] == a["samples"] / 60
        assert b.intervals[k, 0] <= b.stability[k] <= b.intervals[k, 1]
    df = b.to_pandas()
    assert list(df["name"]) == b.names and list(df["points"]) == [a["points"] for a in theirs["attractors"]]
    # In a temporary file: the same, without a file.
    t = paper.basins(x=BASIN_X, y=BASIN_V, samples=60, progress=False, **BASIN_SET)
    d = t.to_dict()
    assert d.pop("file") is None
    theirs.pop("file")
    assert d == theirs and np.array_equal(t.ids, b.ids)


def test_basins_bad_inputs(cli, paper, tmp_path):
    with pytest.raises(errors.InputError, match="must be a positive integer"):
        paper.basins(x=(0, 1, 0), y=BASIN_V, progress=False, **BASIN_SET)
    with pytest.raises(errors.InputError) as e:
        paper.basins(x=BASIN_X, y=BASIN_V, phase=float("nan"), progress=False, **BASIN_SET)
    assert "not a finite number" in str(e.value)
    with pytest.raises(errors.InputError, match="expected"):
        paper.basins(x=("x", 0, 1, 3), y=BASIN_V, progress=False)
    with pytest.raises(errors.InputError, match="at least 0"):
        paper.basins(x=BASIN_X, y=BASIN_V, samples=-1, progress=False)
    with pytest.raises(errors.ParamError) as e:
        paper.basins(x=BASIN_X, y=BASIN_V, samples=0, progress=False, c=-1)
    assert str(e.value) == cli.error(
        "basins", "--set", "c=-1", "--x", "x=0:1:2", "--y", "v=0:1:2", "--out", str(tmp_path / "no.csv")
    )
    out = tmp_path / "b.csv"
    paper.basins(x=BASIN_X, y=BASIN_V, samples=0, out=out, progress=False, **BASIN_SET)
    with pytest.raises(errors.InputError, match="resume=True"):
        paper.basins(x=BASIN_X, y=BASIN_V, samples=0, out=out, progress=False, **BASIN_SET)
    with pytest.raises(errors.InputError, match="different basin run"):
        paper.basins(x=BASIN_X, y=BASIN_V, samples=5, out=out, resume=True, progress=False, **BASIN_SET)


# ---------------------------------------------------------------- progress


def test_no_progress_prints_nothing(paper, capfd):
    paper.map(x=("W", 0.2, 8, 20), y=("Q0", 0, 180, 20), progress=False)
    paper.basins(x=BASIN_X, y=BASIN_V, samples=200, progress=False, **BASIN_SET)
    captured = capfd.readouterr()
    assert captured.err == "" and captured.out == ""


class Recorder:
    """Stands in for ``stickslip._progress.Bar``: records what it is told."""

    made: List["Recorder"] = []

    def __init__(self, total: int, what: str) -> None:
        self.total, self.what, self.seen, self.closed = total, what, [], False
        Recorder.made.append(self)

    def update_to(self, done: int) -> None:
        self.seen.append(done)

    def close(self) -> None:
        self.closed = True


@pytest.mark.parametrize("what", ["map", "basins"])
def test_progress_follows_the_points(paper, monkeypatch, what):
    import stickslip._progress as progress

    monkeypatch.setattr(progress, "Bar", Recorder)
    Recorder.made = []
    # Each call long enough (well past the bar's first 0.1 s, on a fast
    # machine too) for the bar to appear: a 40 x 40 basin grid stopped
    # drawing one once the event search got faster.
    if what == "map":
        paper.map(x=("W", 0.2, 8, 80), y=("Q0", 0, 180, 80), method="simulation")
        total = 6400
    else:
        paper.basins(x=(-5, 5, 150), y=(-10, 10, 150), samples=2500, **BASIN_SET)
        total = 25000
    assert len(Recorder.made) == 1
    bar = Recorder.made[0]
    assert (bar.total, bar.what, bar.closed) == (total, what, True)
    assert bar.seen == sorted(bar.seen) and bar.seen[-1] == total


def test_progress_draws_a_bar(paper, capfd):
    paper.map(x=("W", 0.2, 8, 80), y=("Q0", 0, 180, 80), method="simulation")
    err = capfd.readouterr().err
    assert "map" in err and "6400" in err
