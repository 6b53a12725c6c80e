"""ctc from Python: run and check `.ctc` decks.

    import ctc
    r = ctc.run("examples/hertz_cylinder.ctc", out="out/hertz")
    r.completed, r.summary["newton_iterations"]
    r.history["time"], r.history["contact_force(disc.arc -> floor)_y"]   # NumPy arrays
    r.displacement[-1]          # (nodes, dim) array of the last converged increment
    ctc.check(text="material m { elastic { E = 1 nuu = 0.3 } }")   # diagnostics

The runs are the `ctc run` runs (same compiler, same engine, same files in
the output directory: VTU, PVD, history.csv, summary.json); histories and
fields come back as NumPy arrays.
"""

import csv
import json
import os
from dataclasses import dataclass, field
from typing import Dict, List, Optional

import numpy as np

from . import _ctc
from ._ctc import DeckError

__all__ = ["run", "check", "read_history", "Result", "Diagnostic", "DeckError"]
__version__ = _ctc.__version__


@dataclass
class Diagnostic:
    """One diagnostic of a deck."""

    severity: str
    """`error` or `warning`."""
    message: str
    """What is wrong, in one line."""
    file: str
    """The file it is in (the deck, or a file it includes)."""
    line: int
    """1-based line."""
    column: int
    """1-based column (characters)."""
    rendered: str
    """As `ctc check` prints it: location, source line, caret, help."""


@dataclass
class Result:
    """A run: what `ctc run` wrote, with histories and fields as arrays."""

    completed: bool
    """Whether the whole analysis finished."""
    failure: Optional[str]
    """The diagnosis of a run that stopped early (None when completed)."""
    out: str
    """The output directory."""
    dimension: int
    """2 (plane strain, plane stress, axisymmetric) or 3."""
    coordinates: np.ndarray
    """(nodes, dimension) reference coordinates."""
    times: np.ndarray
    """(increments,) time at the end of each converged increment."""
    displacement: np.ndarray
    """(increments, nodes, dimension) nodal displacements."""
    reaction: np.ndarray
    """(increments, nodes, dimension) nodal reactions (non-zero at constrained dofs)."""
    summary: Dict = field(repr=False)
    """summary.json."""
    history: Dict[str, np.ndarray] = field(repr=False)
    """history.csv, one array per column."""


def read_history(path: str) -> Dict[str, np.ndarray]:
    """The columns of a `history.csv` (a file or its directory) as arrays."""
    if os.path.isdir(path):
        path = os.path.join(path, "history.csv")
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return {}
    header, body = rows[0], [r for r in rows[1:] if r]
    data = np.array([[float(v) for v in r] for r in body], dtype=float).reshape(len(body), len(header))
    return {name: data[:, k].copy() for k, name in enumerate(header)}


def check(path: Optional[str] = None, *, text: Optional[str] = None, name: Optional[str] = None) -> List[Diagnostic]:
    """Every diagnostic of a deck (a path, or `text=` with an optional
    `name=` that labels it and resolves its relative files)."""
    return [Diagnostic(*d) for d in _ctc.check(path, text, name)]


def run(
    path: Optional[str] = None,
    *,
    text: Optional[str] = None,
    name: Optional[str] = None,
    out: Optional[str] = None,
) -> Result:
    """Compiles and runs a deck as `ctc run` does, into `out` (default
    `out/<deck stem>`). A deck with errors raises `DeckError` (its message
    is the rendered diagnostics); a run that stops early returns
    `completed=False` and its `failure`."""
    completed, failure, out_dir, dim, coords, times, u, r = _ctc.run(path, text, name, out)
    nn = len(coords)
    with open(os.path.join(out_dir, "summary.json")) as f:
        summary = json.load(f)
    return Result(
        completed=completed,
        failure=failure,
        out=out_dir,
        dimension=dim,
        coordinates=np.array(coords, dtype=float).reshape(nn, dim),
        times=np.array(times, dtype=float),
        displacement=np.array(u, dtype=float).reshape(len(times), nn, dim),
        reaction=np.array(r, dtype=float).reshape(len(times), nn, dim),
        summary=summary,
        history=read_history(out_dir),
    )
