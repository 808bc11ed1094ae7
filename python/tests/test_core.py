"""The package against the CLI (the same Rust code, run as a process) and the
reference cases: models and parameters, `simulate`, `orbit`, histories,
`sweep`, and every exception type raised by a real bad input."""

from __future__ import annotations

import csv
import io
import json
import math
import os
import pathlib

import numpy as np
import pytest

import stickslip
from conftest import SHARED, close


@pytest.fixture(scope="module")
def paper() -> stickslip.Model:
    return stickslip.Model("paper")


def test_models_are_the_clis(cli):
    listed = [line.split()[0] for line in cli.run("models").stdout.splitlines() if line[:1].strip()]
    assert stickslip.models() == listed


def test_params_are_the_models_declarations(paper, cli):
    described = cli.json("describe", "--model", "paper")
    assert list(paper.params) == list(described["params"])
    for name, p in paper.params.items():
        assert p.default == described["params"][name]
    assert paper.params["W"].bounds == ((">", 0.0),)
    assert paper.params["W"].free


def test_describe_is_the_clis(paper, cli):
    d = paper.describe(W=4, Q0=60)
    assert d.to_dict() == cli.json("describe", "--model", "paper", "--set", "W=4,Q0=60")
    assert str(d) == cli.run("describe", "--model", "paper", "--set", "W=4,Q0=60").stdout


def reference_orbits():
    return json.loads((SHARED / "reference" / "orbits.json").read_text())["orbits"]


@pytest.mark.parametrize("ref", reference_orbits(), ids=lambda r: f"{r['structure']}@W={r['W']}")
def test_reference_motions(paper, cli, ref):
    """The reference cases (computed independently): switching points and
    eigenvalues; the report equals the CLI's to 1e-12 (the same code: bit for bit)."""
    first = ref["switching_points"][0]
    guess = (first["Wt"], first["x"])
    params = dict(W=ref["W"], Q0=ref["Q0"])
    m = paper.orbit(ref["structure"], guess=guess, periods=ref["N_periods"], **params)
    assert m.kind == "periodic"
    want = np.array([[p["Wt"], p["x"], p["v"]] for p in ref["switching_points"]])
    np.testing.assert_allclose(m.points, want, rtol=0, atol=1e-9)
    lam = np.array([complex(*e) for e in ref["eigenvalues"]])
    np.testing.assert_allclose(np.sort_complex(m.eigenvalues), np.sort_complex(lam), atol=1e-8)
    clis = cli.json(
        "orbit",
        "--structure",
        ref["structure"],
        "--set",
        f"W={ref['W']},Q0={ref['Q0']}",
        "--periods",
        str(ref["N_periods"]),
        "--guess",
        f"{guess[0]},{guess[1]}",
    )
    close(m.to_dict(), clis)


@pytest.mark.parametrize(
    "params,start",
    [
        (dict(W=5, Q0=70), (0, 0, 0)),
        (dict(W=3.7, Q0=70), (0.5, 1.0, 1.0)),
        (dict(W=0.3, Q0=70), (0, 0, 0)),  # NM
        (dict(W=1.0, Q0=5), (0, 0, 0)),
    ],
)
def test_simulate_is_the_clis(paper, cli, params, start):
    m = paper.simulate(start=start, **params)
    sets = ",".join(f"{k}={v}" for k, v in params.items())
    frm = ",".join(str(float(u)) for u in start)
    close(m.to_dict(), cli.json("simulate", "--set", sets, "--from", frm))


def read_csv(text: str) -> dict:
    rows = list(csv.DictReader(io.StringIO(text)))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


@pytest.mark.parametrize("params", [dict(W=5, Q0=70), dict(W=0.3, Q0=70)])
def test_history_is_the_clis_csv(paper, cli, tmp_path, params):
    sets = ",".join(f"{k}={v}" for k, v in params.items())
    path = tmp_path / "h.csv"
    out = cli.run("simulate", "--set", sets, "--csv", str(path))
    assert out.returncode == 0, out.stderr
    want = read_csv(path.read_text())
    h = paper.simulate(**params).history()
    assert len(h) == len(want["t"])
    names = {"t": "t", "Wt": "Wt", "x": "x", "v": "v", "a": "a", "F": "F", "domain": "domain"}
    for ours, theirs in names.items():
        np.testing.assert_allclose(getattr(h, ours), want[theirs], rtol=1e-12, atol=1e-12)


def test_history_repeats_a_periodic_motion_exactly(paper):
    m = paper.simulate(W=5, Q0=70)
    one, three = m.history(), m.history(periods=3, samples=100)
    n = len(m.history(samples=100))
    assert len(three) == 3 * n
    period_t = 2 * math.pi * m.N / 5.0
    np.testing.assert_allclose(three.t[2 * n : 3 * n] - 2 * period_t, three.t[:n], rtol=1e-13)
    np.testing.assert_array_equal(three.x[2 * n :], three.x[:n])
    # The repeated cycle closes: the motion's last sample is its first, one period on.
    assert abs(one.x[-1] - one.x[0]) < 1e-9 and abs(one.v[-1] - one.v[0]) < 1e-9
    df = one.to_pandas()
    assert list(df.columns) == list(stickslip.History.COLUMNS) and len(df) == len(one)


def test_motion_fields(paper):
    m = paper.simulate(W=5, Q0=70)
    assert m.structure.startswith("P_{") and m.N == 1 and m.stable and m.admissible
    assert m.points.shape == (len(m.mappings), 3)
    # |λ| < 1 for a stable motion, as the report's stability says.
    assert np.all(np.abs(m.eigenvalues) < 1)
    assert list(m.to_pandas()["mapping"]) == m.mappings
    assert "found by simulation; W = 5, Q0 = 70" in m.title


def test_sweep_is_the_clis(paper, cli):
    s = paper.sweep("W", np.linspace(3.0, 4.0, 21), Q0=70)
    close(s.to_dict(), cli.json("sweep", "--param", "W=3:4:21", "--set", "Q0=70"))
    assert s.values.shape == (21,)
    assert len(s.to_pandas()) == sum(len(p["motions"]) for p in s.points)
    b = s.branch_arrays(0)
    assert b["W"].shape == b["stable"].shape == b["max_abs_x"].shape


def test_sweep_amplitudes_are_the_clis_csv(paper, cli, tmp_path):
    """The frequency response: every motion's max |x| and max |v| in
    ``to_pandas()``, as the CLI's ``--csv`` writes them."""
    s = paper.sweep("W", np.linspace(3.0, 4.0, 11), Q0=70)
    path = tmp_path / "s.csv"
    out = cli.run("sweep", "--param", "W=3:4:11", "--set", "Q0=70", "--csv", str(path))
    assert out.returncode == 0, out.stderr
    rows = list(csv.DictReader(io.StringIO(path.read_text())))
    df = s.to_pandas()
    assert len(df) == len(rows)
    assert list(df["structure"]) == [r["structure"] for r in rows]
    for col in ("W", "start_x", "max_abs_x", "max_abs_v"):
        want = [float(r[col]) if r[col] else np.nan for r in rows]
        np.testing.assert_allclose(df[col], want, rtol=1e-12)
    # Every switching point lies within the amplitude.
    for p in s.points:
        for m in p["motions"]:
            if m["structure"] != "NM":
                assert abs(m["start_x"]) <= m["max_abs_x"] + 1e-12


def test_sweep_without_unstable_is_the_clis(paper, cli):
    s = paper.sweep("W", np.linspace(3.0, 4.0, 11), unstable=False, Q0=70)
    want = cli.json("sweep", "--param", "W=3:4:11", "--set", "Q0=70", "--no-unstable")
    close(s.to_dict(), want)


def test_sweep_max_mappings_is_the_clis(cli):
    """Into stribeck8's period-doubling cascade: no branch of more than 16
    mappings is followed, as the CLI's ``--max-mappings 16``; 0 is an input
    error."""
    s8 = stickslip.Model("stribeck8")
    s = s8.sweep("W", np.linspace(2.5, 2.51, 12), max_mappings=16, Q0=2.5)
    want = cli.json("sweep", "--model", "stribeck8", "--param", "W=2.5:2.51:12",
                    "--set", "Q0=2.5", "--max-mappings", "16")
    close(s.to_dict(), want)
    assert all(len(b["structure"].split()) <= 16 for b in want["branches"])
    with pytest.raises(stickslip.InputError, match="max_mappings"):
        s8.sweep("W", [2.5, 2.51], max_mappings=0, Q0=2.5)


def test_sweep_takes_an_uneven_grid(paper):
    """An uneven grid: each grid value's motions are those at that value."""
    values = [3.0, 3.05, 3.5, 3.9, 4.0]
    s = paper.sweep("W", values, Q0=70)
    assert s.values.tolist() == values
    for p in s.points:
        for mo in p["motions"]:
            if mo.get("structure", "").startswith("P_{3_33 4_33}") and mo.get("N") == 1:
                again = paper.orbit("P_{3_33 4_33}", guess=(mo["start_Wt"], mo["start_x"]), W=p["W"], Q0=70)
                assert abs(again.points[0, 1] - mo["start_x"]) < 1e-9


# Every exception type, from a real bad input, with the CLI's message.


def test_model_error(cli):
    with pytest.raises(stickslip.ModelError) as e:
        stickslip.Model("nope")
    assert isinstance(e.value, ValueError)
    assert str(e.value) == cli.error("describe", "--model", "nope")


def test_model_error_from_a_bad_model_file(tmp_path, cli):
    bad = tmp_path / "bad.ssm"
    bad.write_text("model bad {\n    params { m: f64 = 1.0 }\n    nonsense here\n}\n")
    with pytest.raises(stickslip.ModelError) as e:
        stickslip.check(bad)
    assert f"{bad}:3:" in str(e.value)
    out = cli.run("check", str(bad))
    assert out.returncode != 0 and str(e.value).splitlines()[0] in out.stderr


def test_check_accepts_a_good_model_file():
    assert stickslip.check(stickslip_models_dir() / "coulomb.ssm") == "coulomb"


def stickslip_models_dir():
    from conftest import REPO

    return REPO / "models"


@pytest.mark.parametrize(
    "params,cli_set",
    [(dict(W=-1), "W=-1"), (dict(Wx=2), "Wx=2"), (dict(W=float("nan")), "W=NaN")],
)
def test_param_error(paper, cli, params, cli_set):
    with pytest.raises(stickslip.ParamError) as e:
        paper.simulate(**params)
    assert isinstance(e.value, ValueError)
    assert str(e.value) == cli.error("simulate", "--set", cli_set)


def test_param_error_of_a_sweep(paper, cli):
    with pytest.raises(stickslip.ParamError) as e:
        paper.sweep("Q9", [1, 2])
    assert str(e.value) == cli.error("sweep", "--param", "Q9=1:2:2")


def test_structure_error(paper, cli):
    with pytest.raises(stickslip.StructureError) as e:
        paper.orbit("P_{9_99}", W=5)
    assert isinstance(e.value, ValueError)
    assert str(e.value) == cli.error("orbit", "--structure", "P_{9_99}", "--set", "W=5")


@pytest.mark.parametrize(
    "call",
    [
        lambda m: m.simulate(start=(0, 0), W=5),
        lambda m: m.simulate(start=(0, float("inf"), 0), W=5),
        lambda m: m.orbit("P_{3_33 4_33}", guess=(1, 2, 3), W=5),
        lambda m: m.sweep("W", [4.0, 3.0]),
        lambda m: m.sweep("W", [[3.0, 4.0]]),
        lambda m: m.simulate(periods=0, W=5),
        lambda m: m.simulate(W=5).history(samples=0),
    ],
)
def test_input_error(paper, call):
    with pytest.raises(stickslip.InputError):
        call(paper)


def test_newton_error(paper, cli):
    args = dict(W=0.5, Q0=70)
    with pytest.raises(stickslip.NewtonError) as e:
        paper.orbit("P_{3_31 0_11 3_13 4_33}", **args)
    assert isinstance(e.value, RuntimeError)
    assert e.value.result.kind == "not_converged"
    assert str(e.value) == cli.error("orbit", "--structure", "P_{3_31 0_11 3_13 4_33}", "--set", "W=0.5,Q0=70")


def test_inadmissible_error(paper, cli):
    with pytest.raises(stickslip.InadmissibleError) as e:
        paper.orbit("P_{3_33 4_33}", W=3.7, Q0=70)
    r = e.value.result
    assert r.kind == "inadmissible" and r.admissible is False and r.violations
    assert str(e.value) == cli.error("orbit", "--structure", "P_{3_33 4_33}", "--set", "W=3.7,Q0=70")
    close(r.to_dict(), json.loads(cli.run("orbit", "--structure", "P_{3_33 4_33}", "--set", "W=3.7,Q0=70", "--json").stdout))


def test_unsettled_error(paper, cli):
    with pytest.raises(stickslip.UnsettledError) as e:
        paper.simulate(periods=5, W=3.7)
    assert str(e.value) == cli.error("simulate", "--set", "W=3.7", "--periods", "5")


def test_seed_error(paper):
    # P_{3_33} alone is no motion any simulation follows at W = 5.
    with pytest.raises(stickslip.SeedError) as e:
        paper.orbit("P_{1_11 1_11}", W=0.3, Q0=70)
    assert "give the first switching point with guess=(Wt, x)" in str(e.value)


def test_guess_off_the_structure_warns_and_seeds_by_simulation(paper):
    with pytest.warns(UserWarning, match="seeding by simulation instead"):
        m = paper.orbit("P_{3_33 4_33}", guess=(1, 50), W=3, Q0=70)
    assert m.kind == "periodic"


def test_simulation_error():
    """A start far outside any bound motion: the flow overflows."""
    m = stickslip.Model("coulomb")
    with pytest.raises(stickslip.SimulationError) as e:
        m.simulate(start=(1e308, 1e308, 0.0))
    assert isinstance(e.value, RuntimeError)


def test_errors_are_stickslip_errors():
    for name in stickslip.errors.__all__:
        assert issubclass(getattr(stickslip, name), stickslip.StickslipError)


def test_the_readme_example_runs(tmp_path):
    """examples/readme.py is the README's ten-line example: it runs and draws."""
    import runpy

    from conftest import REPO

    pytest.importorskip("matplotlib")
    pytest.importorskip("pandas")
    import matplotlib

    matplotlib.use("Agg")
    (tmp_path / "docs" / "guide" / "src" / "figures").mkdir(parents=True)
    cwd = pathlib.Path.cwd()
    os.chdir(tmp_path)
    try:
        runpy.run_path(str(REPO / "examples" / "readme.py"))
    finally:
        os.chdir(cwd)
    assert (tmp_path / "docs" / "guide" / "src" / "figures" / "python_example.png").stat().st_size > 10_000


def test_orbit_diagram_is_the_clis(cli):
    m = stickslip.Model("stribeck8")
    d = m.orbit_diagram("W", 2.2, 2.45, 6, transient=60, periods=12, lyapunov=60, Q0=3)
    want = cli.json(
        "orbit-diagram", "--model", "stribeck8", "--param", "W=2.2:2.45:6", "--set", "Q0=3",
        "--transient", "60", "--periods", "12", "--lyapunov", "60",
    )
    close(d.to_dict(), want)
    s = d.samples("down")
    assert s["W"].shape == s["x"].shape == (6 * 12,)
    assert d.exponents().shape == (6,)


def test_orbit_diagram_errors(paper, cli):
    with pytest.raises(stickslip.ParamError) as e:
        paper.orbit_diagram("Q9", 1, 2, 3)
    assert str(e.value) == cli.error("orbit-diagram", "--param", "Q9=1:2:3")
    with pytest.raises(stickslip.InputError):
        paper.orbit_diagram("W", 1, 2, 3, periods=0)
