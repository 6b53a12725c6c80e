"""The 3D Hertz sphere pair of issue 20 (verification/fenicsx/sphere3d.py and
sphere3d.sh) stays in step with ctc (run by python/test.sh, from .ci/run).

Reference: DOLFINx 0.11.0.post0 on the same mesh and penalty,
verification/reference/fenicsx011_sphere3d_n6.json, written by
`sphere3d.py DIR --n 6` in the DOLFINx 0.11 venv (install-0.11.sh; CI has
no DOLFINx 0.11, so the reference is committed). The script's export (numpy
only) writes the gmsh mesh and the ctc deck; `ctc run` of that deck must
solve the same free dofs as DOLFINx and agree with it within the
discretization difference of the two penalties (the tutorial's vertical gap
at facet quadrature points against ctc's nodal normal gap to the exact
sphere): contact force 1.4 %, peak pressure 0.09 % at N = 6, checked to
3 % and 1 %.

    rigid sphere R = 1 pressed d = 0.02 into a graded P1 quarter block
    [0, 2]^2 x [-2, 0]: N = 6 cubes per direction, 6 tetrahedra each
"""

import csv
import glob
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("CTC_BIN", os.path.join(ROOT, "target", "debug", "ctc"))
SCRIPT = os.path.join(ROOT, "verification", "fenicsx", "sphere3d.py")
REFERENCE = os.path.join(ROOT, "verification", "reference", "fenicsx011_sphere3d_n6.json")


class Sphere3dPairInStep(unittest.TestCase):
    def test_the_exported_deck_runs_and_agrees_with_dolfinx(self):
        with open(REFERENCE) as f:
            ref = json.load(f)
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run([sys.executable, SCRIPT, tmp, "--n", "6", "--export-only"], check=True)
            with open(os.path.join(tmp, "mesh.json")) as f:
                mesh = json.load(f)
            self.assertEqual(mesh["free_dofs"], ref["free_dofs"])
            # 10 E / h_min from numpy: its last bit moves with numpy's
            # version (python/test.sh installs the newest: 2.4.6 on
            # 2026-12-06 gave 190264.2071506396, the reference ...962)
            self.assertLess(abs(mesh["penalty"] / ref["penalty"] - 1.0), 1e-12, (mesh["penalty"], ref["penalty"]))
            out = os.path.join(tmp, "ctc")
            subprocess.run([CLI, "run", os.path.join(tmp, "sphere3d.ctc"), "-q", "-o", out], check=True)
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
            self.assertTrue(summary["completed"], summary["failure"])
            self.assertEqual(summary["free_dofs"], ref["free_dofs"])
            self.assertEqual(len(summary["increments"]), len(ref["iterations_per_increment"]))
            last = sorted(glob.glob(os.path.join(out, "contact_0_*.csv")))[-1]
            with open(last) as f:
                rows = list(csv.DictReader(f))
            force = -sum(float(r["force_z"]) for r in rows)
            axis = min(rows, key=lambda r: float(r["x"]) ** 2 + float(r["y"]) ** 2)
            self.assertAlmostEqual(float(axis["x"]) ** 2 + float(axis["y"]) ** 2, 0.0)
            peak = float(axis["pressure"])
            self.assertLess(abs(force / ref["contact_force"] - 1.0), 0.03, (force, ref["contact_force"]))
            self.assertLess(abs(peak / ref["peak_pressure"] - 1.0), 0.01, (peak, ref["peak_pressure"]))


if __name__ == "__main__":
    unittest.main()
