"""The finite-strain Neo-Hooke indentation pair of issue 20
(verification/fenicsx/neo_indent.py and neo_indent.sh) stays in step with
ctc (run by python/test.sh, from .ci/run).

Reference: DOLFINx 0.11.0.post0 on the same mesh, strain energy, circle and
penalty, contact integrated at the edge vertices (ctc's node-to-segment
penalty against a rigid tool, the same discrete problem),
verification/reference/fenicsx011_neo_indent_24.json, written by
`neo_indent.py DIR --rule vertex` (24 x 12 cells, 10 increments) in the
DOLFINx 0.11 venv (install-0.11.sh; CI has no DOLFINx 0.11, so the
reference is committed). The committed deck and mesh
verification/fenicsx/cases/neo_indent.ctc / neo_indent_24x12.msh must be
what the script exports (numpy only), and `ctc run` of that deck must
- solve the same free dofs;
- give the vertical force on the circle at every increment (d = R/20 ..
  R/2) within 1e-9 of DOLFINx's (measured 5.1e-11 at most, increment 9,
  where ctc stopped at a relative residual of 7.8e-11; both Newton
  tolerances 1e-10);
- need no more Newton iterations than DOLFINx (issue 20's bar; measured 31
  against 71, `bash verification/fenicsx/neo_indent.sh 1 24`; 70 before
  the increment predictor was used at finite strain).

    rigid circle R = 1 pressed to R/2 into a plane strain Neo-Hooke block
    [-3, 3] x [-3, 0] (E = 10, nu = 0.3), bottom clamped, area penalty
    10 E / h: 24 x 12 cells, 4 crossed-diagonal P1 triangles each
"""

import csv
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("CTC_BIN", os.path.join(ROOT, "target", "debug", "ctc"))
HERE = os.path.join(ROOT, "verification", "fenicsx")
SCRIPT = os.path.join(HERE, "neo_indent.py")
DECK = os.path.join(HERE, "cases", "neo_indent.ctc")
MESH = os.path.join(HERE, "cases", "neo_indent_24x12.msh")
REFERENCE = os.path.join(ROOT, "verification", "reference", "fenicsx011_neo_indent_24.json")


class NeoIndentPairInStep(unittest.TestCase):
    def test_the_committed_deck_is_the_export_and_agrees_with_dolfinx(self):
        with open(REFERENCE) as f:
            ref = json.load(f)
        self.assertEqual(ref["rule"], "vertex")
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run([sys.executable, SCRIPT, tmp, "--nx", "24", "--ny", "12", "--steps", "10",
                            "--export-only"], check=True)
            with open(os.path.join(tmp, "mesh.json")) as f:
                mesh = json.load(f)
            self.assertEqual(mesh["free_dofs"], ref["free_dofs"])
            self.assertEqual(mesh["penalty"], ref["penalty"])
            with open(os.path.join(tmp, "neo_indent.msh")) as a, open(MESH) as b:
                self.assertEqual(a.read(), b.read(), "regenerate cases/neo_indent_24x12.msh")
            with open(os.path.join(tmp, "neo_indent.ctc")) as a, open(DECK) as b:
                exported = a.read().replace('"neo_indent.msh"', '"neo_indent_24x12.msh"')
                self.assertEqual(exported, b.read(), "regenerate cases/neo_indent.ctc")
            work = os.path.join(tmp, "case")
            os.makedirs(work)
            shutil.copy(DECK, work)
            shutil.copy(MESH, work)
            out = os.path.join(tmp, "ctc")
            subprocess.run([CLI, "run", os.path.join(work, "neo_indent.ctc"), "-q", "-o", out], check=True)
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
            self.assertTrue(summary["completed"], summary["failure"])
            self.assertEqual(summary["free_dofs"], ref["free_dofs"])
            steps = len(ref["iterations_per_increment"])
            self.assertEqual(len(summary["increments"]), steps)
            paths = sorted(glob.glob(os.path.join(out, "contact_0_*.csv")))
            self.assertEqual(len(paths), steps)
            for k, path in enumerate(paths):
                with open(path) as f:
                    force = -sum(float(r["force_y"]) for r in csv.DictReader(f))
                self.assertLess(abs(force / ref["force"][k] - 1.0), 1e-9, (k + 1, force, ref["force"][k]))
            self.assertLessEqual(summary["newton_iterations"], ref["newton_iterations"],
                                 [i["iterations"] for i in summary["increments"]])


if __name__ == "__main__":
    unittest.main()
