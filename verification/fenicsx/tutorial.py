#!/usr/bin/env python3
"""The tutorial-style 2D Hertz problem of issue 20 solved by DOLFINx 0.11
(SNES), and the same mesh and tool exported for ctc (see SPEED.md,
`tutorial.sh`).

Problem (J. Bleyer, comet-fenicsx, "Hertzian contact with a rigid indenter
using a penalty approach", in 2D): P1 vectors on a 200 x 100 rectangle with
crossed diagonals (4 triangles per cell), graded by x = 4 sinh(5 s) / sinh(5),
s in [-1, 1], and y = -4 sinh(5 (1 - s)) / sinh(5), s in [0, 1] (fine at the
top centre), so the block is [-4, 4] x [-4, 0]; E = 1e3, nu = 0.3, plane
strain, bottom clamped; rigid parabola y = -d + x^2 / 2 (R = 1) pressed to
d = 0.02 in 4 steps; penalty `pen * ppos(u_y - obstacle) * v_y * ds(top)`,
`pen = 10 E / h_min` (h_min the shortest mesh edge), obstacle evaluated at
the reference coordinates (the tutorial's small-displacement gap), facet
quadrature degree 2; SNES newtonls with the basic line search,
rtol = atol = 1e-10, KSP preonly + LU (MUMPS).

    ^ y
    |      \\      parabola y = -d + x^2/2     /
    |        `--.__________________________.--'
  0 +--------------------------------------------+  top: penalty facets
    |   sinh-graded crossed-diagonal P1 mesh      |
 -4 +--------------------------------------------+  bottom: clamped
   -4                    0                       4   x

Usage: tutorial.py OUTDIR [--steps 4] [--nx 200 --ny 100] [--export-only]
       tutorial.py --table DIR   (the table of the runs tutorial.sh left in
                                  DIR: ctc_<rep>/, fx_<rep>/fenicsx.json)
Writes OUTDIR/tutorial.msh (gmsh 2.2: the same nodes and triangles, physical
lines `top` and `bottom`), OUTDIR/tutorial.ctc (ctc deck on that mesh, the
parabola as an exact quadratic NURBS, area penalty 10 E / h_min) and
OUTDIR/fenicsx.json (Newton iterations per step, loop wall and CPU time,
total contact force, peak pressure at the axis node).
"""

import argparse
import json
import os
import time

try:  # the wheel's shared libraries first (DOLFINx 0.11 from dolfinx-solver-real)
    import dolfinx_solver  # noqa: F401
except ImportError:
    pass

import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem
import dolfinx.fem.petsc
import dolfinx.mesh

E, NU, DEPTH, BETA = 1e3, 0.3, 0.02, 5.0


def graded_mesh(nx, ny):
    m = dolfinx.mesh.create_rectangle(
        MPI.COMM_SELF,
        [np.array([-1.0, 0.0]), np.array([1.0, 1.0])],
        [nx, ny],
        dolfinx.mesh.CellType.triangle,
        diagonal=dolfinx.mesh.DiagonalType.crossed,
    )
    x = m.geometry.x
    s, t = x[:, 0].copy(), x[:, 1].copy()
    x[:, 0] = 4.0 * np.sinh(BETA * s) / np.sinh(BETA)
    x[:, 1] = -4.0 * np.sinh(BETA * (1.0 - t)) / np.sinh(BETA)
    return m


def shortest_edge(m):
    m.topology.create_entities(1)
    m.topology.create_connectivity(1, 2)
    n = m.topology.index_map(1).size_local
    g = dolfinx.mesh.entities_to_geometry(m, 1, np.arange(n, dtype=np.int32))
    x = m.geometry.x
    return float(np.min(np.linalg.norm(x[g[:, 0], :2] - x[g[:, 1], :2], axis=1)))


def write_gmsh(m, path):
    """gmsh 2.2 ASCII: nodes, counter-clockwise triangles, top and bottom
    boundary lines as physical groups 1 `top` and 2 `bottom`."""
    x = m.geometry.x[:, :2]
    dofmap = m.geometry.dofmaps[0] if hasattr(m.geometry, "dofmaps") else m.geometry.dofmap
    cells = np.asarray(dofmap).reshape(-1, 3).copy()
    a, b, c = x[cells[:, 0]], x[cells[:, 1]], x[cells[:, 2]]
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    flip = area < 0
    cells[flip, 1], cells[flip, 2] = cells[flip, 2].copy(), cells[flip, 1].copy()
    m.topology.create_connectivity(1, 2)
    lines = []
    for tag, y in ((1, 0.0), (2, -4.0)):
        facets = dolfinx.mesh.locate_entities_boundary(m, 1, lambda p, y=y: np.isclose(p[1], y))
        g = dolfinx.mesh.entities_to_geometry(m, 1, facets)
        lines += [(tag, int(p), int(q)) for p, q in g]
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write('$PhysicalNames\n3\n1 1 "top"\n1 2 "bottom"\n2 3 "block"\n$EndPhysicalNames\n')
        f.write(f"$Nodes\n{len(x)}\n")
        for i, p in enumerate(x):
            f.write(f"{i + 1} {float(p[0])!r} {float(p[1])!r} 0\n")
        f.write(f"$EndNodes\n$Elements\n{len(lines) + len(cells)}\n")
        k = 1
        for tag, p, q in lines:
            f.write(f"{k} 1 2 {tag} {tag} {p + 1} {q + 1}\n")
            k += 1
        for t in cells:
            f.write(f"{k} 2 2 3 3 {t[0] + 1} {t[1] + 1} {t[2] + 1}\n")
            k += 1
        f.write("$EndElements\n")


def ctc_deck(msh, penalty, steps):
    # the parabola y = x^2 / 2 over [-1, 1] as a quadratic Bezier (exact):
    # walked from +x to -x so that the block (below) is on its left
    return f"""# Issue 20, tutorial-style 2D Hertz: the DOLFINx mesh (tutorial.py) with the
# parabola y = -d + x^2 / 2 as an exact quadratic NURBS, area penalty 10 E / h_min.
# Generated by verification/fenicsx/tutorial.py; run: ctc run tutorial.ctc
analysis {{ dimension = plane_strain }}
material elastic {{ elastic {{ E = {E:e}  nu = {NU} }} }}
body block {{ mesh = file "{os.path.basename(msh)}"  material = elastic }}
tool punch = nurbs {{
  degree = 2  points = [(1, 0.5), (0, -0.5), (-1, 0.5)]
  motion {{ uy = ramp(0, -{DEPTH}) }}
}}
contact block.top -> punch {{ method = penalty {{ kind = area  stiffness = {float(penalty)!r} }} }}
fix block.bottom {{ ux uy }}
step press {{
  time = 0 .. 1
  increments = {steps}
  newton {{ tol = 1e-10  tol_displacement = 1e-10 }}
}}
output {{ fields = [displacement, contact] }}
"""


def ctc_result(d):
    """Iterations, loop time (engine total less output), process CPU,
    total contact force and axis pressure of a `ctc run` directory."""
    import csv
    import glob

    with open(os.path.join(d, "summary.json")) as f:
        s = json.load(f)
    with open(os.path.join(d, "cpu.txt")) as f:
        user, sys_ = (float(v) for v in f.read().split()[:2])
    last = sorted(glob.glob(os.path.join(d, "contact_0_*.csv")))[-1]
    with open(last) as f:
        rows = list(csv.DictReader(f))
    axis = min(rows, key=lambda r: float(r["x"]) ** 2)
    t = s["timings"]
    return {
        "free_dofs": s["free_dofs"],
        "iterations_per_increment": [i["iterations"] for i in s["increments"]],
        "newton_iterations": s["newton_iterations"],
        "wall_time": t["total"] - t["output"],
        "cpu_time": user + sys_,
        "contact_force": -sum(float(r["force_y"]) for r in rows),
        "peak_pressure": float(axis["pressure"]),
        "linear_solver": f"{s['linear_solver']} ({s['ldlt_factorizations'] + s['cholesky_factorizations'] + s['lu_factorizations']} factorizations, {s.get('low_rank_updates', 0)} low-rank updates)",
        "factorization": t["factorization"],
        "low_rank": t.get("low_rank", 0.0),
        "peak_memory_bytes": s.get("peak_memory_bytes", 0),
        "threads": s.get("threads", 1),
        "timings": t,
    }


def table(directory):
    import glob

    def runs(prefix, read):
        return [read(d) for d in sorted(glob.glob(os.path.join(directory, prefix + "_*")))]

    ctc = runs("ctc", ctc_result)
    fx = runs("fx", lambda d: json.load(open(os.path.join(d, "fenicsx.json"))))
    if not ctc or not fx:
        raise SystemExit(f"no runs in {directory}")
    if {r["free_dofs"] for r in ctc} != {r["free_dofs"] for r in fx}:
        raise SystemExit("ctc and FEniCSx solved different numbers of free dofs")
    base = min(ctc, key=lambda r: r["wall_time"])
    base_cpu = min(r["cpu_time"] for r in ctc)
    print("| code | free dofs | Newton its | per increment | loop wall, min [s] | all runs [s] | CPU, min [s] | linear solver | wall / ctc | CPU / ctc | its / ctc |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name, rs in (("ctc", ctc), (f"DOLFINx {fx[0]['dolfinx']}", fx)):
        best = min(rs, key=lambda r: r["wall_time"])
        cpu = min(r["cpu_time"] for r in rs)
        print(
            f"| {name} | {best['free_dofs']} | {best['newton_iterations']} | {best['iterations_per_increment']} "
            f"| {best['wall_time']:.3f} | {' '.join(f'{r['wall_time']:.3f}' for r in rs)} | {cpu:.3f} "
            f"| {best['linear_solver']} | {best['wall_time'] / base['wall_time']:.2f} | {cpu / base_cpu:.2f} "
            f"| {best['newton_iterations'] / base['newton_iterations']:.2f} |"
        )
    print()
    print("| quantity | ctc | DOLFINx | rel. diff |")
    print("|---|---|---|---|")
    for q in ("contact_force", "peak_pressure"):
        a, b = ctc[0][q], fx[0][q]
        print(f"| {q.replace('_', ' ')} | {a:.7g} | {b:.7g} | {abs(a - b) / abs(b):.1e} |")
    its = base["newton_iterations"]
    print()
    print(
        f"ctc per iteration: {1e3 * base['wall_time'] / its:.1f} ms loop, "
        f"{1e3 * base['factorization'] / its:.1f} ms in factorization + low-rank updates "
        f"(low-rank {1e3 * base['low_rank']:.0f} ms in all); peak memory "
        f"{base['peak_memory_bytes'] / 2**20:.0f} MiB; {base['threads']} thread(s). ctc's CPU is the whole process "
        "(mesh reading and output included): an upper bound of its loop."
    )
    t = base["timings"]
    phases = ["setup", "assembly", "contact", "symbolic", "factorization", "low_rank", "solve", "residual"]
    other = t["total"] - t["output"] - sum(t.get(p, 0.0) for p in phases if p not in ("symbolic", "low_rank"))
    print()
    print("ctc phases of that run [ms]: " + ", ".join(
        f"{p} {1e3 * t.get(p, 0.0):.0f}" for p in phases) + f", other {1e3 * other:.0f}, "
        f"output {1e3 * t['output']:.0f} (not in the loop time); symbolic and low_rank are parts of factorization.")


def main():
    import sys

    if len(sys.argv) == 3 and sys.argv[1] == "--table":
        table(sys.argv[2])
        return
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--steps", type=int, default=4)
    ap.add_argument("--nx", type=int, default=200)
    ap.add_argument("--ny", type=int, default=100)
    ap.add_argument("--export-only", action="store_true")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    m = graded_mesh(args.nx, args.ny)
    h_min = shortest_edge(m)
    pen = 10.0 * E / h_min
    msh = os.path.join(args.out, "tutorial.msh")
    write_gmsh(m, msh)
    with open(os.path.join(args.out, "tutorial.ctc"), "w") as f:
        f.write(ctc_deck(msh, pen, args.steps))
    if args.export_only:
        return

    V = dolfinx.fem.functionspace(m, ("Lagrange", 1, (2,)))
    mu = E / (2 * (1 + NU))
    lmbda = E * NU / ((1 + NU) * (1 - 2 * NU))

    def eps(w):
        return ufl.sym(ufl.grad(w))

    def sigma(w):
        return lmbda * ufl.tr(eps(w)) * ufl.Identity(2) + 2 * mu * eps(w)

    def ppos(z):
        return (z + abs(z)) / 2

    fdim = 1
    bottom = dolfinx.mesh.locate_entities_boundary(m, fdim, lambda p: np.isclose(p[1], -4.0))
    top = dolfinx.mesh.locate_entities_boundary(m, fdim, lambda p: np.isclose(p[1], 0.0))
    tags = dolfinx.mesh.meshtags(m, fdim, np.sort(top), np.full(len(top), 1, dtype=np.int32))
    bc = dolfinx.fem.dirichletbc(
        np.zeros(2, dtype=PETSc.ScalarType),
        dolfinx.fem.locate_dofs_topological(V, fdim, bottom),
        V,
    )
    ds = ufl.Measure("ds", domain=m, subdomain_data=tags, metadata={"quadrature_degree": 2})
    u = dolfinx.fem.Function(V)
    v = ufl.TestFunction(V)
    d = dolfinx.fem.Constant(m, PETSc.ScalarType(0.0))
    x = ufl.SpatialCoordinate(m)
    obstacle = -d + x[0] ** 2 / 2
    penetration = ppos(u[1] - obstacle)
    F = ufl.inner(sigma(u), eps(v)) * ufl.dx + pen * penetration * v[1] * ds(1)
    opts = {
        "snes_type": "newtonls",
        "snes_linesearch_type": "basic",
        "snes_rtol": 1e-10,
        "snes_atol": 1e-10,
        "ksp_type": "preonly",
        "pc_type": "lu",
        "pc_factor_mat_solver_type": "mumps",
    }
    problem = dolfinx.fem.petsc.NonlinearProblem(
        F, u, bcs=[bc], petsc_options=opts, petsc_options_prefix="hertz_"
    )
    snes = problem.solver
    its = []
    wall0, cpu0 = time.perf_counter(), time.process_time()
    for k in range(1, args.steps + 1):
        d.value = DEPTH * k / args.steps
        problem.solve()
        reason = snes.getConvergedReason()
        if reason <= 0:
            raise SystemExit(f"SNES diverged at step {k} (reason {reason})")
        its.append(int(snes.getIterationNumber()))
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    force = dolfinx.fem.assemble_scalar(dolfinx.fem.form(pen * penetration * ds(1)))
    # peak pressure: the axis vertex's consistent force over its tributary
    # length (int p N_i / int N_i), the analogue of ctc's nodal pressure
    Q = dolfinx.fem.functionspace(m, ("Lagrange", 1))
    w = ufl.TestFunction(Q)
    fp = dolfinx.fem.assemble_vector(dolfinx.fem.form(pen * penetration * w * ds(1))).array
    fl = dolfinx.fem.assemble_vector(dolfinx.fem.form(w * ds(1))).array
    xq = Q.tabulate_dof_coordinates()
    axis = int(np.argmin(xq[:, 0] ** 2 + xq[:, 1] ** 2))
    n_bottom = int(np.sum(np.isclose(m.geometry.x[:, 1], -4.0)))
    out = {
        "dolfinx": dolfinx.__version__,
        "free_dofs": 2 * (len(m.geometry.x) - n_bottom),
        "h_min": h_min,
        "penalty": pen,
        "iterations_per_increment": its,
        "newton_iterations": int(sum(its)),
        "wall_time": wall,
        "cpu_time": cpu,
        "contact_force": float(force),
        "peak_pressure": float(fp[axis] / fl[axis]),
        "linear_solver": "mumps lu",
    }
    with open(os.path.join(args.out, "fenicsx.json"), "w") as f:
        json.dump(out, f, indent=1)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
