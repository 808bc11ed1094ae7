#!/usr/bin/env python3
"""Codimension-two points of `curves` runs whose second curve is not traced.

At a codimension-two end of a curve of motion S (its condition meeting a
second one), the curve of S's second condition passes through the same
point. This counts, per JSON file of `stickslip curves --json` (e.g. the
runs of `benches/curves-runs.sh`, kept in target/curves-runs/):

* codimension-two points at which only one traced curve ends;
* of those, the ones with no traced curve of the same motion (any rotation
  of its structure) and of the second kind within 1e-3 of the box
  (distance in each parameter over the span of the curves' points), by
  pair of kinds (the ending curve's, the missing one's).

An upper bound on missing curves, not a count: where an excursion shrank
to nothing the second curve is the reduced motion's (another structure),
and a kind may be named differently on the two curves.

    python3 benches/curves-partners.py target/curves-runs/*.json
"""
import json
import sys
from collections import Counter


def canonical(name):
    periods = ""
    if "}^" in name:
        name, periods = name.split("}^")
        name += "}"
    tokens = name[3:-1].split()
    rotations = [tuple(tokens[i:] + tokens[:i]) for i in range(len(tokens))] or [()]
    return min(rotations), periods


for path in sys.argv[1:]:
    d = json.load(open(path))
    x, y = d["x"], d["y"]
    xs = [p[0] for c in d["curves"] for p in c["points"]]
    ys = [p[1] for c in d["curves"] for p in c["points"]]
    sx, sy = (max(xs) - min(xs)) or 1.0, (max(ys) - min(ys)) or 1.0
    one = [p for p in d["codim2"] if len(p["curves"]) == 1]
    missing = []
    for p in one:
        c = d["curves"][p["curves"][0]]
        kinds = list(p["kinds"])
        kinds.remove(c["kind"])
        second = kinds[0] if kinds else c["kind"]
        near = [
            min(abs(q[0] - p[x]) / sx + abs(q[1] - p[y]) / sy for q in other["points"])
            for other in d["curves"]
            if other["kind"] == second and canonical(other["structure"]) == canonical(c["structure"])
        ]
        if not near or min(near) > 1e-3:
            missing.append((c["kind"], second))
    print(
        f"{path}: {len(d['codim2'])} codim-2 points, {len(one)} with one curve ending, "
        f"{len(missing)} with no second curve of that motion nearby; "
        + ", ".join(f"{a} -> {b}: {n}" for (a, b), n in Counter(missing).most_common(4))
    )
