"""Models loaded at run time: a model with a friction law of its own, written
to a file during the test, loaded by the installed wheel (built once, with
no model of this kind in it), simulated and swept, and compared with the CLI
run on the same file with ``--model-file``; ``Model.from_source``; a rejected
file raises ``ModelError`` with ``stickslip check``'s report."""

from __future__ import annotations

import numpy as np
import pytest

import stickslip

from conftest import REPO, close

# Written now, so it cannot be compiled into the wheel: a falling branch just
# above the belt speed, a rising one beyond it, Coulomb friction below.
OWN_LAW = """
//! A mass on a belt with a friction law of its own.
model own_law {
    /// Mass.
    param m = 1.0, > 0;
    /// Damping per unit mass.
    param d = 0.08, >= 0;
    /// Stiffness per unit mass.
    param c = 1.0, > 0;
    /// Belt speed.
    param V = 0.6;
    /// Where the friction starts to rise again.
    param V1 = 1.2;
    /// Static level.
    param fs = 0.5, >= 0;
    /// Kinetic level at the belt speed.
    param fk = 0.3, >= 0;
    /// Falling slope.
    param s1 = 0.4;
    /// Rising slope.
    param s2 = 0.2;
    /// Forcing amplitude.
    param Q0 = 0.6;
    /// Forcing frequency.
    param W = 0.9, > 0;

    oscillator { mass: m, damping: d, stiffness: c, forcing: Q0 / m, frequency: W }

    /// Belt speed.
    boundary Sigma1: v = V, stick fs;
    /// Slope change.
    boundary Sigma2: v = V1;

    /// Above V1: rising.
    domain 2: v > Sigma2 => fk - s1 * (V1 - V) + s2 * (v - V1);
    /// Between V and V1: falling.
    domain 1: Sigma1 < v < Sigma2 => fk - s1 * (v - V);
    /// Below the belt speed.
    domain 3: v < Sigma1 => -fk;
}
"""


@pytest.fixture()
def own_law(tmp_path):
    path = tmp_path / "own_law.ssm"
    path.write_text(OWN_LAW)
    return path


def test_a_new_law_is_loaded_simulated_and_swept_as_the_cli_does(own_law, cli):
    assert "own_law" not in stickslip.models()
    m = stickslip.Model.from_file(own_law)
    assert m.name == "own_law"
    assert list(m.params)[:3] == ["m", "d", "c"]
    assert "from_file" in repr(m)
    sim = m.simulate(W=0.9, Q0=0.6)
    close(sim.to_dict(), cli.json("simulate", "--model-file", str(own_law), "--set", "W=0.9,Q0=0.6"))
    assert sim.kind == "periodic"
    s = m.sweep("W", np.linspace(0.6, 1.2, 13), Q0=0.6)
    want = cli.json("sweep", "--model-file", str(own_law), "--param", "W=0.6:1.2:13", "--set", "Q0=0.6")
    close(s.to_dict(), want)
    assert len(want["points"]) == 13


def test_a_model_from_source_is_the_model_from_its_file(own_law):
    a = stickslip.Model.from_file(own_law).simulate(W=1.0)
    b = stickslip.Model.from_source(OWN_LAW).simulate(W=1.0)
    close(a.to_dict(), b.to_dict(), tol=0.0)


def test_a_shipped_model_file_is_the_compiled_model_with_its_scenes():
    path = REPO / "models" / "paper.ssm"
    loaded = stickslip.Model.from_file(path, scene="sweep_w")
    assert loaded.name == "paper::sweep_w"
    assert list(loaded.params) == list(stickslip.Model("paper::sweep_w").params)
    a = loaded.simulate(W=3.7).to_dict()
    b = stickslip.Model("paper::sweep_w").simulate(W=3.7).to_dict()
    close(a, b, tol=1e-10)


def test_a_rejected_file_raises_model_error_with_the_report_check_gives(tmp_path):
    path = tmp_path / "own_law.ssm"
    path.write_text(OWN_LAW.replace("fk - s1 * (v - V)", "fk - s1 * (v - VV)"))
    with pytest.raises(stickslip.ModelError) as loaded:
        stickslip.Model.from_file(path)
    with pytest.raises(stickslip.ModelError) as checked:
        stickslip.check(path)
    assert str(loaded.value) == str(checked.value)
    assert f"--> {path}:" in str(loaded.value)
    with pytest.raises(stickslip.ModelError, match="has no scene `nope`"):
        stickslip.Model.from_file(REPO / "models" / "paper.ssm", scene="nope")
    with pytest.raises(stickslip.ModelError, match="<source>:"):
        stickslip.Model.from_source("model broken {")
