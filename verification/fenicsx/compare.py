#!/usr/bin/env python3
"""Compares a freshly regenerated FEniCSx reference with the committed one.

Usage: compare.py COMMITTED.json FRESH.json [rtol]

Passes when the nodal displacements and contact forces agree to `rtol`
(default 1e-9, relative to the largest vector) and the Newton iteration
counts are equal: the reference is reproducible on this machine.
"""

import json
import sys

import numpy as np


def rel(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape:
        return float("inf")
    scale = np.max(np.linalg.norm(b.reshape(-1, 2), axis=1)) if b.size else 0.0
    diff = np.max(np.linalg.norm((a - b).reshape(-1, 2), axis=1)) if b.size else 0.0
    return diff / scale if scale > 0 else diff


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    with open(sys.argv[1]) as fh:
        old = json.load(fh)
    with open(sys.argv[2]) as fh:
        new = json.load(fh)
    rtol = float(sys.argv[3]) if len(sys.argv) == 4 else 1e-9
    du = rel(new["displacement"], old["displacement"])
    df = max([rel(n, o) for n, o in zip(new["contact_forces"], old["contact_forces"])] or [0.0])
    same_pairs = len(new["contact_forces"]) == len(old["contact_forces"])
    same_newton = new["newton_iterations"] == old["newton_iterations"]
    print(
        f"{old['case']}: displacement {du:.1e}, contact forces {df:.1e}, Newton "
        f"{new['newton_iterations']} (committed {old['newton_iterations']})"
    )
    if not (du <= rtol and df <= rtol and same_pairs and same_newton):
        sys.exit(f"{old['case']}: the regenerated reference differs from the committed one")


if __name__ == "__main__":
    main()
