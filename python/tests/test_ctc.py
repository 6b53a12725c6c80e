"""The Python package against the CLI (run by python/test.sh, from .ci/run).

Reference: `ctc run` itself. The Python run and the CLI run of
examples/hertz_cylinder.ctc must write the same history.csv byte for byte
(one compiler, one engine, deterministic), and the arrays handed to Python
must be the numbers in the files: the contact force in the history equals
minus the sum of the reactions of the clamped flat side, to 1e-10 relative
(equilibrium of the half cylinder pressed on the rigid floor).

    rigid floor y = 0   <-  disc.arc (slave)    disc.flat (displaced down, reactions)
"""

import os
import subprocess
import tempfile
import unittest

import numpy as np

import ctc

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("CTC_BIN", os.path.join(ROOT, "target", "debug", "ctc"))
DECK = os.path.join(ROOT, "examples", "hertz_cylinder.ctc")


class RunMatchesTheCli(unittest.TestCase):
    def test_hertz_cylinder_forces_equal_the_cli_run(self):
        with tempfile.TemporaryDirectory() as tmp:
            py_out, cli_out = os.path.join(tmp, "py"), os.path.join(tmp, "cli")
            r = ctc.run(DECK, out=py_out)
            subprocess.run([CLI, "run", DECK, "-q", "-o", cli_out], check=True)
            self.assertTrue(r.completed, r.failure)
            with open(os.path.join(py_out, "history.csv")) as a, open(os.path.join(cli_out, "history.csv")) as b:
                self.assertEqual(a.read(), b.read())
            cli = ctc.read_history(cli_out)
            key = "contact_force(disc.arc -> floor)_y"
            np.testing.assert_array_equal(r.history[key], cli[key])
            # the arrays are the run's: reactions summed over disc.flat
            flat = np.isclose(r.coordinates[:, 1], 8.0)
            self.assertGreater(flat.sum(), 10)
            total = r.reaction[:, flat, 1].sum(axis=1)
            np.testing.assert_allclose(total, r.history["reaction(disc.flat)_y"], rtol=1e-12)
            np.testing.assert_allclose(-total, r.history[key], rtol=1e-10)
            self.assertEqual(r.displacement.shape, (len(r.times), len(r.coordinates), 2))
            np.testing.assert_array_equal(r.times, r.history["time"])
            self.assertEqual(r.summary["increments"][-1]["time"], 1.0)
            self.assertEqual(r.summary["completed"], True)


class Diagnostics(unittest.TestCase):
    def test_a_misspelled_key_is_located_with_a_suggestion(self):
        with open(DECK) as f:
            original = f.read()
        text = original.replace("nu = 0.3", "nuu = 0.3", 1)
        self.assertNotEqual(text, original)
        ds = ctc.check(text=text, name=DECK)
        errors = [d for d in ds if d.severity == "error"]
        self.assertEqual(len(errors), 1, [d.rendered for d in ds])
        e = errors[0]
        line = text.splitlines()[e.line - 1]
        self.assertEqual(line[e.column - 1 : e.column + 2], "nuu")
        self.assertIn("nu", e.rendered)
        self.assertIn("^", e.rendered)
        self.assertEqual(ctc.check(DECK), [])

    def test_a_deck_with_errors_raises_with_the_rendered_diagnostics(self):
        with self.assertRaises(ctc.DeckError) as cm:
            ctc.run(text="analysis { dimension = plane_strain }\nmaterial m { elastic { E = -1 nu = 0.3 } }\n")
        self.assertIn("deck.ctc:2:", str(cm.exception))

    def test_a_missing_deck_is_an_os_error(self):
        with self.assertRaises(OSError):
            ctc.run("no/such/deck.ctc")


if __name__ == "__main__":
    unittest.main()
