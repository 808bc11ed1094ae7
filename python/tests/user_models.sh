#!/usr/bin/env bash
# User models at build time, end to end: `STICKSLIP_MODELS=dir pip install ./python`
# compiles dir/*.ssm in beside models/*.ssm, and a broken user model fails the
# install with its error located in the user's file (dir/bad.ssm:LINE:COL).
#
# The user model `mine` is the checkout's `coulomb` renamed: the same
# equations, so it must settle to exactly coulomb's motion.
#
# Usage: bash python/tests/user_models.sh  (from anywhere; builds into a
# throwaway venv; needs python3 with venv, numpy and maturin installable).
set -euo pipefail
cd "$(dirname "$0")/../.."

tmp=$(mktemp -d "${TMPDIR:-/tmp}/stickslip-user-models.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/good" "$tmp/bad"
sed 's/^model coulomb {/model mine {/' models/coulomb.ssm > "$tmp/good/mine.ssm"
grep -q '^model mine {' "$tmp/good/mine.ssm"
# A broken model: an unknown name, at a place found here independently.
sed 's/^model coulomb {/model bad {/; s/let FN = m \* g;/let FN = m * gee;/' \
    models/coulomb.ssm > "$tmp/bad/bad.ssm"
line=$(grep -n 'gee;' "$tmp/bad/bad.ssm" | cut -d: -f1)
col=$(awk -v l="$line" 'NR == l { print index($0, "gee") }' "$tmp/bad/bad.ssm")
where="$tmp/bad/bad.ssm:$line:$col"

python3 -m venv "$tmp/venv"
py="$tmp/venv/bin/python"
export PATH="$tmp/venv/bin:$PATH"  # maturin's Python shim runs `maturin` from PATH
unset STICKSLIP_MODELS
"$py" -m pip install -q numpy maturin

echo "== a broken user model fails the install at $where"
if STICKSLIP_MODELS="$tmp/bad" "$py" -m pip install --no-build-isolation ./python \
    > "$tmp/bad.log" 2>&1; then
    echo "FAIL: the install with a broken user model succeeded" >&2
    exit 1
fi
if ! grep -qF -- "--> $where" "$tmp/bad.log" || ! grep -qF "unknown name \`gee\`" "$tmp/bad.log"; then
    echo "FAIL: the install's output does not locate the error at $where:" >&2
    cat "$tmp/bad.log" >&2
    exit 1
fi
grep -F -B1 -A4 -- "--> $where" "$tmp/bad.log"
echo "(${SECONDS}s so far)"

echo "== a good user model is compiled in"
STICKSLIP_MODELS="$tmp/good" "$py" -m pip install -q --no-build-isolation ./python
cd "$tmp"  # import the installed package, not the checkout's source
"$py" - <<'PY'
import numpy as np
import stickslip

names = stickslip.models()
assert "mine" in names and "coulomb" in names and "paper" in names, names
mine, coulomb = stickslip.Model("mine"), stickslip.Model("coulomb")
assert list(mine.params) == list(coulomb.params)
for p in (dict(), dict(W=1.3, Q0=0.9)):
    a = mine.simulate(start=(0.1, 0.0, 0.0), **p)
    b = coulomb.simulate(start=(0.1, 0.0, 0.0), **p)
    assert a.kind == b.kind and a.structure == b.structure, (a, b)
    assert np.array_equal(np.asarray(a.points), np.asarray(b.points)), (a.points, b.points)
    ha, hb = a.history(samples=50), b.history(samples=50)
    assert len(ha) > 0 and np.array_equal(ha.x, hb.x)
    print(f"mine {p or 'defaults'}: {a.kind} {a.structure}, N = {a.N}: as coulomb")
PY
echo "user models: ok (${SECONDS}s)"
