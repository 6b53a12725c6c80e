#!/usr/bin/env python3
"""Finite-strain Neo-Hooke indentation of issue 20 solved by DOLFINx 0.11
(SNES), and the same mesh, material, tool and penalty exported for ctc
(see SPEED.md, section "Neo-Hooke indentation", and `neo_indent.sh`).

Problem (plane strain, total Lagrangian): a block [-W, W] x [-H, 0],
W = H = 3, bottom clamped, sides and top free; compressible Neo-Hooke,
the strain energy ctc implements (engine/src/material/law.rs)

    W(F) = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,
    I1 = tr(F^T F) + 1 (F_33 = 1), J = det F,
    mu = E / (2 (1 + nu)), lambda = E nu / ((1 + nu) (1 - 2 nu)),

E = 10, nu = 0.3; a rigid circle of radius R = 1, centre (0, R - d),
touching the top at the origin at d = 0 and pressed to d = R/2 in `steps`
equal increments (default 10). Frictionless penalty contact on the top
edge: gap to the exact circle at the current position x = X + u,
g = |x - c| - R, normal n = (x - c) / |x - c|, traction on the block
k <-g>_+ n per unit reference length, k = 10 E / h (h the top edge length;
ctc's `penalty { kind = area }`). Weak form
int P(F) : grad v dX - int_top k <-g>_+ n . v dS = 0, with its exact
Jacobian (UFL `derivative`, including the turn of n).

The contact integral is evaluated either
- `--rule vertex` (default): at the edge end points with weight L/2, which
  is ctc's node-to-segment penalty against a rigid tool exactly (nodal gap
  to the circle times the reference tributary length, see
  engine/src/contact/tributary.rs): the same discrete problem, so forces
  agree to the Newton tolerance;
- `--rule gauss`: Gauss degree 2 on each edge (the FEniCSx tutorials' style,
  gap at the quadrature points): a different contact discretization; its
  force difference to ctc is the discretization difference.

Mesh: nx x ny uniform cells, each split by its two diagonals into 4 P1
triangles (a node at the centre), built here with numpy: DOLFINx receives
it through `create_mesh`, ctc through the gmsh file, so `--export-only`
needs numpy only (python/tests/test_neo_indent.py runs it and `ctc run`).

    y ^       rigid circle R = 1, centre (0, R - d), d = 0 .. R/2
      |             .-~~~-.
      |            (   +   )
    0 +-------------`-----'------------+  top: penalty edges
      |  crossed-diagonal P1 triangles |
   -H +--------------------------------+  bottom: clamped
     -W                0               W  x

Newton: SNES newtonls with PETSc's default line search (bt; `--linesearch
basic` for plain full steps), rtol = atol = 1e-10 (||F|| <= 1e-10 ||F_0||,
F_0 the residual at the increment's start, or ||F|| <= 1e-10) and PETSc's
default stol = 1e-8 (||du|| <= 1e-8 ||u||), as a user runs it, max_it 50;
KSP preonly + LU (MUMPS). ctc: `newton { tol = 1e-10
tol_displacement = 1e-10 max_iter = 50 }` (relative residual against the
external + contact + reaction force scale AND relative correction, see
engine/src/solve/newton/convergence.rs), its default line search and
increment predictor.

Usage: neo_indent.py OUTDIR [--nx 24 --ny 12] [--steps 10] [--export-only]
                            [--rule vertex|gauss] [--linesearch bt|basic]
       neo_indent.py --table DIR   (the runs neo_indent.sh left in DIR:
                                    ctc_<rep>/, fx_<rule>_<rep>/fenicsx.json)
Writes OUTDIR/neo_indent.msh (gmsh 2.2: nodes, triangles, physical lines
`top` and `bottom`), OUTDIR/neo_indent.ctc, OUTDIR/mesh.json (free dofs,
h, penalty) and, unless --export-only, OUTDIR/fenicsx.json (per increment:
Newton iterations, SNES converged reason, residual history, vertical
force on the circle; loop wall and CPU time).
"""

import argparse
import json
import os
import time

import numpy as np

E, NU, R, W, H = 10.0, 0.3, 1.0, 3.0, 3.0
DEPTH = R / 2


def block_mesh(nx, ny):
    """Nodes (grid row by row from the bottom, then the cell centres) and
    counter-clockwise triangles of the crossed-diagonal mesh; top and
    bottom boundary edges."""
    gx = np.linspace(-W, W, nx + 1)
    gy = np.linspace(-H, 0.0, ny + 1)
    yy, xx = np.meshgrid(gy, gx, indexing="ij")
    grid = np.column_stack([xx.ravel(), yy.ravel()])
    cx = 0.5 * (gx[:-1] + gx[1:])
    cy = 0.5 * (gy[:-1] + gy[1:])
    cyy, cxx = np.meshgrid(cy, cx, indexing="ij")
    x = np.vstack([grid, np.column_stack([cxx.ravel(), cyy.ravel()])])
    top = ny  # exact 0.0 at the top row (linspace end point)
    x[top * (nx + 1) : (top + 1) * (nx + 1), 1] = 0.0

    def node(i, j):
        return i + (nx + 1) * j

    cells = []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)
            m = (nx + 1) * (ny + 1) + i + nx * j
            cells += [(a, b, m), (b, c, m), (c, d, m), (d, a, m)]
    top_edges = [(node(i + 1, ny), node(i, ny)) for i in range(nx)]
    bottom_edges = [(node(i, 0), node(i + 1, 0)) for i in range(nx)]
    return x, np.array(cells, dtype=np.int64), top_edges, bottom_edges


def free_dofs(nx, ny):
    nodes = (nx + 1) * (ny + 1) + nx * ny
    return 2 * (nodes - (nx + 1))


def write_gmsh(x, cells, top, bottom, path):
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write('$PhysicalNames\n3\n1 1 "top"\n1 2 "bottom"\n2 3 "block"\n$EndPhysicalNames\n')
        f.write(f"$Nodes\n{len(x)}\n")
        for i, p in enumerate(x):
            f.write(f"{i + 1} {float(p[0])!r} {float(p[1])!r} 0\n")
        f.write(f"$EndNodes\n$Elements\n{len(top) + len(bottom) + len(cells)}\n")
        k = 1
        for tag, lines in ((1, top), (2, bottom)):
            for p, q in lines:
                f.write(f"{k} 1 2 {tag} {tag} {p + 1} {q + 1}\n")
                k += 1
        for t in cells:
            f.write(f"{k} 2 2 3 3 {t[0] + 1} {t[1] + 1} {t[2] + 1}\n")
            k += 1
        f.write("$EndElements\n")


def ctc_deck(msh, penalty, steps):
    return f"""# Issue 20, finite-strain Neo-Hooke indentation: ctc's side of the pair
# (verification/fenicsx/neo_indent.py wrote this deck and its mesh; DOLFINx
# 0.11 solves the same mesh, strain energy, circle and penalty). Plane
# strain block [-{W:g}, {W:g}] x [-{H:g}, 0], crossed-diagonal P1 triangles,
# W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2 (E = {E:g}, nu = {NU});
# rigid circle R = {R:g} pressed to R/2 in {steps} increments; area penalty
# k = 10 E / h (h the top edge length).
# Reference: DOLFINx 0.11, the same discrete problem with the contact
# integrated at the edge vertices (verification/reference/
# fenicsx011_neo_indent_24.json for 24 x 12 cells): forces to the Newton
# tolerance, ctc's Newton iterations <= DOLFINx's (issue 20).
#
#          rigid circle, centre (0, R - d), d = 0 .. R/2
#                 .-~~~-.
#   0 +----------(-------)----------+  block.top: penalty edges
#     |  Neo-Hooke, finite strain   |
#  -{H:g} +-----------------------------+  block.bottom: clamped
#    -{W:g}             0               {W:g}
#
# Run: ctc run neo_indent.ctc
analysis {{ dimension = plane_strain }}
material rubber {{ neo_hookean {{ E = {E:g}  nu = {NU} }} }}
body block {{
  mesh = file "{os.path.basename(msh)}"
  material = rubber
  kinematics = finite
}}
tool punch = circle {{ center = (0, {R:g})  radius = {R:g}  motion {{ uy = ramp(0, -{DEPTH:g}) }} }}
contact block.top -> punch {{ method = penalty {{ kind = area  stiffness = {float(penalty)!r} }} }}
fix block.bottom {{ ux uy }}
step press {{
  time = 0 .. 1
  increments = {steps}
  newton {{ tol = 1e-10  tol_displacement = 1e-10  max_iter = 50 }}
}}
output {{ fields = [displacement, contact] }}
"""


def ctc_result(d):
    """Per increment: iterations, depth, vertical contact force on the
    block's top; loop wall (engine total less output), process wall / CPU."""
    import csv
    import glob

    with open(os.path.join(d, "summary.json")) as f:
        s = json.load(f)
    forces = []
    for path in sorted(glob.glob(os.path.join(d, "contact_0_*.csv"))):
        with open(path) as f:
            rows = list(csv.DictReader(f))
        forces.append(-sum(float(r["force_y"]) for r in rows))
    out = {
        "completed": s["completed"],
        "free_dofs": s["free_dofs"],
        "iterations_per_increment": [i["iterations"] for i in s["increments"]],
        "newton_iterations": s["newton_iterations"],
        "cutbacks": s.get("cutbacks", 0),
        "loop_wall": s["timings"]["total"] - s["timings"]["output"],
        "force": forces,
    }
    t = os.path.join(d, "time.txt")
    if os.path.exists(t):
        wall, user, sys_, rss = open(t).read().split()[:4]
        out.update(process_wall=float(wall), cpu=float(user) + float(sys_), rss_mib=int(rss) / 1024)
    return out


def fx_result(d):
    with open(os.path.join(d, "fenicsx.json")) as f:
        r = json.load(f)
    t = os.path.join(d, "time.txt")
    if os.path.exists(t):
        wall, user, sys_, rss = open(t).read().split()[:4]
        r.update(process_wall=float(wall), cpu=float(user) + float(sys_), rss_mib=int(rss) / 1024)
    return r


def table(directory):
    import glob

    def runs(pattern, read):
        return [read(d) for d in sorted(glob.glob(os.path.join(directory, pattern)))]

    with open(os.path.join(directory, "mesh.json")) as f:
        mesh = json.load(f)
    ctc = runs("ctc_*", ctc_result)
    fx = {rule: runs(f"fx_{rule}_*", fx_result) for rule in ("vertex", "gauss")}
    fx = {k: v for k, v in fx.items() if v}
    if not ctc or not fx:
        raise SystemExit(f"no runs in {directory}")
    for rs in fx.values():
        if {r["free_dofs"] for r in ctc} != {r["free_dofs"] for r in rs}:
            raise SystemExit("ctc and FEniCSx solved different numbers of free dofs")
    c0 = ctc[0]
    steps = mesh["steps"]
    names = list(fx)
    print(f"mesh {mesh['nx']} x {mesh['ny']} cells (crossed diagonals), {mesh['free_dofs']} free dofs, "
          f"h = {mesh['h']:g}, k = {mesh['penalty']:g}, {steps} increments")
    print()
    head = "| incr | d / R | ctc its | " + " | ".join(f"FEniCSx {n} its" for n in names)
    head += " | ctc force | " + " | ".join(f"FEniCSx {n} force | ctc / {n} - 1" for n in names) + " |"
    print(head)
    print("|" + "---|" * (3 + 3 * len(names) + 1))
    for k in range(steps):
        row = f"| {k + 1} | {(k + 1) / steps * DEPTH / R:.2f} | {c0['iterations_per_increment'][k]} | "
        row += " | ".join(
            f"{fx[n][0]['iterations_per_increment'][k] if k < len(fx[n][0]['iterations_per_increment']) else '-'}"
            for n in names)
        row += f" | {c0['force'][k]:.6g} | "
        cells = []
        for n in names:
            f = fx[n][0]["force"]
            cells.append(f"{f[k]:.6g} | {c0['force'][k] / f[k] - 1:+.1e}" if k < len(f) else "- | -")
        row += " | ".join(cells) + " |"
        print(row)
    print()
    print("| code | Newton its | loop wall, min [s] | all runs [s] | process wall, min [s] | process CPU, min [s] | peak RSS [MiB] |")
    print("|---|---|---|---|---|---|---|")

    def line(name, rs, its_key="newton_iterations"):
        walls = [r.get("loop_wall", r.get("wall_time")) for r in rs]
        pw = [r["process_wall"] for r in rs if "process_wall" in r]
        cpu = [r["cpu"] for r in rs if "cpu" in r]
        rss = [r["rss_mib"] for r in rs if "rss_mib" in r]
        fmt = lambda v: f"{min(v):.3f}" if v else "-"  # noqa: E731
        print(f"| {name} | {rs[0][its_key]} | {min(walls):.3f} | {' '.join(f'{w:.3f}' for w in walls)} "
              f"| {fmt(pw)} | {fmt(cpu)} | {max(rss) if rss else 0:.0f} |")

    line("ctc", ctc)
    for n in names:
        rs = fx[n]
        for r in rs:
            r["loop_wall"] = r["wall_time"]
        line(f"DOLFINx {rs[0]['dolfinx']} ({n}, {rs[0]['linesearch']} line search)", rs)
    for n in names:
        reasons = sorted({x for x in fx[n][0]["reasons"]})
        print()
        print(f"SNES converged reasons ({n}): {reasons} (2 ATOL, 3 RTOL, 4 STOL)")
    if c0["cutbacks"]:
        print(f"ctc cutbacks: {c0['cutbacks']}")


def solve(x, cells, nx, ny, out, steps, pen, rule, linesearch):
    # the wheel's shared libraries first (DOLFINx 0.11 from dolfinx-solver-real)
    try:
        import dolfinx_solver  # noqa: F401
    except ImportError:
        pass
    import basix.ufl
    import ufl
    from mpi4py import MPI
    from petsc4py import PETSc

    import dolfinx
    import dolfinx.fem
    import dolfinx.fem.petsc
    import dolfinx.mesh

    domain = ufl.Mesh(basix.ufl.element("Lagrange", "triangle", 1, shape=(2,)))
    m = dolfinx.mesh.create_mesh(MPI.COMM_SELF, cells, domain, x)
    V = dolfinx.fem.functionspace(m, ("Lagrange", 1, (2,)))
    mu = E / (2 * (1 + NU))
    lmbda = E * NU / ((1 + NU) * (1 - 2 * NU))

    fdim = 1
    m.topology.create_connectivity(fdim, 2)
    bottom = dolfinx.mesh.locate_entities_boundary(m, fdim, lambda p: np.isclose(p[1], -H))
    top = dolfinx.mesh.locate_entities_boundary(m, fdim, lambda p: np.isclose(p[1], 0.0))
    tags = dolfinx.mesh.meshtags(m, fdim, np.sort(top), np.full(len(top), 1, dtype=np.int32))
    bc = dolfinx.fem.dirichletbc(
        np.zeros(2, dtype=PETSc.ScalarType), dolfinx.fem.locate_dofs_topological(V, fdim, bottom), V
    )
    if rule == "vertex":
        md = {"quadrature_rule": "vertex", "quadrature_degree": 1}
    else:
        md = {"quadrature_degree": 2}
    ds = ufl.Measure("ds", domain=m, subdomain_data=tags, metadata=md)
    u = dolfinx.fem.Function(V)
    v = ufl.TestFunction(V)
    d = dolfinx.fem.Constant(m, PETSc.ScalarType(0.0))
    X = ufl.SpatialCoordinate(m)
    # Neo-Hooke, plane strain (F_33 = 1)
    F = ufl.Identity(2) + ufl.grad(u)
    J = ufl.det(F)
    I1 = ufl.tr(F.T * F) + 1.0
    psi = mu / 2 * (I1 - 3) - mu * ufl.ln(J) + lmbda / 2 * ufl.ln(J) ** 2
    # gap to the circle at the current position
    c = ufl.as_vector([0.0, R - d])
    xc = X + u - c
    dist = ufl.sqrt(ufl.dot(xc, xc))
    n = xc / dist
    pen_depth = ufl.max_value(R - dist, 0.0)
    traction = pen * pen_depth * n
    residual = ufl.derivative(psi * ufl.dx, u, v) - ufl.dot(traction, v) * ds(1)
    opts = {
        "snes_type": "newtonls",
        "snes_linesearch_type": linesearch,
        "snes_rtol": 1e-10,
        "snes_atol": 1e-10,
        "snes_max_it": 50,
        "ksp_type": "preonly",
        "pc_type": "lu",
        "pc_factor_mat_solver_type": "mumps",
    }
    problem = dolfinx.fem.petsc.NonlinearProblem(
        residual, u, bcs=[bc], petsc_options=opts, petsc_options_prefix="neo_"
    )
    snes = problem.solver
    force_form = dolfinx.fem.form(-traction[1] * ds(1))
    its, reasons, forces, histories = [], [], [], []
    wall0, cpu0 = time.perf_counter(), time.process_time()
    failed = None
    for k in range(1, steps + 1):
        d.value = DEPTH * k / steps
        snes.setConvergenceHistory(length=100, reset=True)
        problem.solve()
        reason = snes.getConvergedReason()
        histories.append([float(r) for r in snes.getConvergenceHistory()[0]])
        if reason <= 0:
            failed = f"SNES diverged at increment {k} (reason {reason})"
            break
        its.append(int(snes.getIterationNumber()))
        reasons.append(int(reason))
        forces.append(float(dolfinx.fem.assemble_scalar(force_form)))
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    result = {
        "dolfinx": dolfinx.__version__,
        "rule": rule,
        "linesearch": linesearch,
        "free_dofs": free_dofs(nx, ny),
        "penalty": pen,
        "iterations_per_increment": its,
        "newton_iterations": int(sum(its)),
        "reasons": reasons,
        "residual_histories": histories,
        "force": forces,
        "wall_time": wall,
        "cpu_time": cpu,
        "failed": failed,
    }
    with open(os.path.join(out, "fenicsx.json"), "w") as f:
        json.dump(result, f, indent=1)
    print(json.dumps({k: v for k, v in result.items() if k != "residual_histories"}))
    if failed:
        raise SystemExit(failed)


def main():
    import sys

    if len(sys.argv) == 3 and sys.argv[1] == "--table":
        table(sys.argv[2])
        return
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--nx", type=int, default=24)
    ap.add_argument("--ny", type=int, default=12)
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--rule", choices=["vertex", "gauss"], default="vertex")
    ap.add_argument("--linesearch", choices=["bt", "basic"], default="bt")
    ap.add_argument("--export-only", action="store_true")
    args = ap.parse_args()
    if args.nx < 1 or args.ny < 1 or args.steps < 1:
        raise SystemExit("--nx, --ny and --steps must be at least 1")
    os.makedirs(args.out, exist_ok=True)
    x, cells, top, bottom = block_mesh(args.nx, args.ny)
    h = 2 * W / args.nx
    pen = 10.0 * E / h
    if args.export_only:
        msh = os.path.join(args.out, "neo_indent.msh")
        write_gmsh(x, cells, top, bottom, msh)
        with open(os.path.join(args.out, "neo_indent.ctc"), "w") as f:
            f.write(ctc_deck(msh, pen, args.steps))
        info = {"nx": args.nx, "ny": args.ny, "steps": args.steps, "nodes": len(x), "triangles": len(cells),
                "free_dofs": free_dofs(args.nx, args.ny), "h": h, "penalty": pen}
        with open(os.path.join(args.out, "mesh.json"), "w") as f:
            json.dump(info, f, indent=1)
        return
    solve(x, cells, args.nx, args.ny, args.out, args.steps, pen, args.rule, args.linesearch)


if __name__ == "__main__":
    main()
