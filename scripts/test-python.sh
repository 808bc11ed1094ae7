#!/usr/bin/env bash
# The Python package, as a user installs it: `pip install ./python` into a
# fresh virtual environment (maturin builds the abi3 wheel with every
# compiled-in model), its pytest suite against the CLI's JSON, and the
# notebook examples/paper.ipynb executed headless; then user models compiled
# in at install time (python/tests/user_models.sh).
#
# Needs python3 (>= 3.9) with venv, PyPI, and the release CLI
# (`cargo build --release`), which the tests compare with.
set -euo pipefail
cd "$(dirname "$0")/.."

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
venv="$work/venv"
python3 -m venv "$venv"
py="$venv/bin/python"
"$py" -m pip install -q --upgrade pip

echo "-- pip install ./python"
start=$SECONDS
"$py" -m pip install -q ./python
echo "   built and installed in $((SECONDS - start)) s"
"$py" -m pip install -q pytest pandas tqdm matplotlib nbclient nbformat ipykernel

cargo build --release -q
export STICKSLIP_CLI="$PWD/target/release/stickslip"

echo "-- pytest python/tests"
# From outside the source tree: the installed wheel is what is tested.
(cd "$work" && "$py" -m pytest -q -p no:cacheprovider "$OLDPWD/python/tests")

echo "-- examples/paper.ipynb, executed headless"
start=$SECONDS
"$py" - <<'PY'
import nbformat
from nbclient import NotebookClient

nb = nbformat.read("examples/paper.ipynb", as_version=4)
NotebookClient(nb, timeout=1200, kernel_name="python3", resources={"metadata": {"path": "examples"}}).execute()
errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", []) if o.get("output_type") == "error"]
assert not errors, errors
print(f"   {sum(c.cell_type == 'code' for c in nb.cells)} code cells ran")
PY
echo "   in $((SECONDS - start)) s"

echo "-- user models: STICKSLIP_MODELS=dir pip install ./python"
bash python/tests/user_models.sh
