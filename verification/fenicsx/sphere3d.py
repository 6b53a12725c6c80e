#!/usr/bin/env python3
"""The 3D Hertz sphere of issue 20 solved by DOLFINx 0.11 (SNES) in the
formulation of the 2D tutorial pair (tutorial.py), and the same mesh and
tool exported for ctc (see SPEED.md, `sphere3d.sh`).

Problem (J. Bleyer, comet-fenics, "Hertzian contact with a rigid indenter
using a penalty approach", 3D quarter model; here with the exact sphere and
the load, material and penalty of tutorial.py): an elastic block
[0, L] x [0, L] x [-L, 0], L = 2, E = 1e3, nu = 0.3, symmetry planes x = 0
(u_x = 0) and y = 0 (u_y = 0), bottom z = -L clamped; a rigid sphere of
radius R = 1 touching the top face z = 0 at the origin, pressed to
d = 0.02 in 4 steps (Hertz: a = sqrt(R d) = 0.141, whole-sphere force
P = 4/3 E / (1 - nu^2) sqrt(R) d^(3/2) = 4.145, this quarter carries
P / 4, p0 = 3 P / (2 pi a^2) = 98.9 for a half-space). Mesh: N x N x N
cubes, each split into the 6 tetrahedra of the Kuhn (Freudenthal)
triangulation (P1, conforming), graded towards the contact point by
x = L sinh(beta s) / sinh(beta), s in [0, 1] (same for y and for -z),
beta = 4. Penalty `pen * ppos(u_z - obstacle) * v_z * ds(top)` with
`pen = 10 E / h_min` (h_min the shortest mesh edge), obstacle the sphere
below its centre at the reference (x, y): `R - d - sqrt(R^2 - x^2 - y^2)`
(the tutorial's small-displacement vertical gap), facet quadrature degree
2; SNES newtonls with the basic line search, rtol = atol = 1e-10,
KSP preonly + LU (MUMPS).

        z ^   rigid sphere R = 1, centre (0, 0, R - d)
          |        .-~~~-.
          |      /         \\
        0 +-----------------+---> x     top z = 0: penalty facets
          |  graded P1 tets |           x = 0: u_x = 0, y = 0: u_y = 0
       -L +-----------------+           bottom z = -L: clamped
          0                 L

The mesh is built here with numpy (the same nodes and tetrahedra for both
codes: DOLFINx receives them through `create_mesh`, ctc through the gmsh
file), so `--export-only` needs numpy only (the CI test of the pair,
python/tests/test_sphere3d.py, runs it and `ctc run` on a small mesh).

Usage: sphere3d.py OUTDIR [--n 40] [--steps 4] [--export-only] [--stop-after K]
       sphere3d.py --table DIR   (the table of the runs sphere3d.sh left in
                                  DIR: ctc_<rep>/, fx_<rep>/fenicsx.json)
Writes OUTDIR/sphere3d.msh (gmsh 2.2: nodes, tetrahedra, physical surfaces
`top`, `xsym`, `ysym`, `bottom`), OUTDIR/sphere3d.ctc (ctc deck on that
mesh, the exact sphere, area penalty 10 E / h_min), OUTDIR/mesh.json (free
dofs, h_min, penalty) and, unless --export-only, OUTDIR/fenicsx.json
(Newton iterations per step, loop wall and CPU time, total contact force
of the quarter, peak pressure at the axis node).
"""

import argparse
import json
import math
import os
import time

import numpy as np

E, NU, R, DEPTH, L, BETA = 1e3, 0.3, 1.0, 0.02, 2.0, 4.0

# Kuhn triangulation of the unit cube: one tetrahedron per order of the
# axes, walking from corner (0, 0, 0) to (1, 1, 1) along +e_p0, +e_p1, +e_p2
KUHN = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]


def graded(n):
    """Node coordinates along one axis: L sinh(beta s) / sinh(beta), s = k / n."""
    s = np.arange(n + 1) / n
    return L * np.sinh(BETA * s) / np.sinh(BETA)


def box_mesh(n):
    """Nodes (x fastest, then y, then z; z from -L to 0) and positively
    oriented tetrahedra of the graded N x N x N box."""
    g = graded(n)
    gz = -g[::-1]  # fine at z = 0
    zz, yy, xx = np.meshgrid(gz, g, g, indexing="ij")
    x = np.column_stack([xx.ravel(), yy.ravel(), zz.ravel()])

    def node(i, j, k):
        return i + (n + 1) * (j + (n + 1) * k)

    i, j, k = (a.ravel() for a in np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij"))
    tets = []
    for order in KUHN:
        c = [node(i, j, k)]
        o = [0, 0, 0]
        for p in order:
            o[p] += 1
            c.append(node(i + o[0], j + o[1], k + o[2]))
        tets.append(np.column_stack(c))
    cells = np.vstack(tets).astype(np.int64)
    # positive volume (the Kuhn tetrahedra of odd permutations are mirrored)
    a, b, c, d = (x[cells[:, q]] for q in range(4))
    vol = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))
    flip = vol < 0
    cells[flip, 1], cells[flip, 2] = cells[flip, 2].copy(), cells[flip, 1].copy()
    return x, cells


def boundary_triangles(n):
    """Triangles of the four boundary planes used: name -> (m, 3) node
    numbers (the faces of the Kuhn tetrahedra on those planes)."""

    def node(i, j, k):
        return i + (n + 1) * (j + (n + 1) * k)

    a, b = (v.ravel() for v in np.meshgrid(np.arange(n), np.arange(n), indexing="ij"))

    def plane(f):
        # corners (a, b), (a+1, b), (a, b+1), (a+1, b+1) of each square; the
        # Kuhn split cuts every square of a coordinate plane along the
        # diagonal from its lower to its upper corner
        p00, p10, p01, p11 = f(a, b), f(a + 1, b), f(a, b + 1), f(a + 1, b + 1)
        return np.vstack([np.column_stack([p00, p10, p11]), np.column_stack([p00, p11, p01])])

    return {
        "top": plane(lambda p, q: node(p, q, n)),
        "bottom": plane(lambda p, q: node(p, q, 0)),
        "xsym": plane(lambda p, q: node(0, p, q)),
        "ysym": plane(lambda p, q: node(p, 0, q)),
    }


def free_dofs(n):
    """Free dofs of the model: 3 per node less the clamped bottom and one
    component on each symmetry plane (nodes on both: two)."""
    nodes = (n + 1) ** 3
    bottom = (n + 1) ** 2
    sym = 2 * (n + 1) * n  # x = 0 and y = 0 above the bottom
    return 3 * nodes - 3 * bottom - sym


def write_gmsh(x, cells, faces, path):
    """gmsh 2.2 ASCII: nodes, tetrahedra (physical volume 5 `block`), the
    boundary triangles as physical surfaces 1-4."""
    names = ["top", "xsym", "ysym", "bottom"]
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write(f"$PhysicalNames\n{len(names) + 1}\n")
        for t, name in enumerate(names, 1):
            f.write(f'2 {t} "{name}"\n')
        f.write('3 5 "block"\n$EndPhysicalNames\n')
        f.write(f"$Nodes\n{len(x)}\n")
        f.write("".join(f"{i + 1} {p[0]!r} {p[1]!r} {p[2]!r}\n" for i, p in enumerate(x.tolist())))
        total = sum(len(faces[nm]) for nm in names) + len(cells)
        f.write(f"$EndNodes\n$Elements\n{total}\n")
        k = 1
        lines = []
        for t, name in enumerate(names, 1):
            for p, q, r in (faces[name] + 1).tolist():
                lines.append(f"{k} 2 2 {t} {t} {p} {q} {r}\n")
                k += 1
        for a, b, c, d in (cells + 1).tolist():
            lines.append(f"{k} 4 2 5 5 {a} {b} {c} {d}\n")
            k += 1
        f.write("".join(lines))
        f.write("$EndElements\n")


def ctc_deck(msh, penalty, steps):
    return f"""# Issue 20, 3D Hertz sphere side by side with DOLFINx 0.11: the mesh of
# verification/fenicsx/sphere3d.py (graded P1 tetrahedra, quarter model), the
# rigid sphere R = {R} exact, area penalty 10 E / h_min on the top face.
# Reference: Hertz (K. L. Johnson, Contact Mechanics, 1985, section 4.2) and
# DOLFINx 0.11 on the same mesh (SPEED.md). Generated by sphere3d.py;
# run: ctc run sphere3d.ctc
analysis {{ dimension = 3d }}
material elastic {{ elastic {{ E = {E:e}  nu = {NU} }} }}
body block {{ mesh = file "{os.path.basename(msh)}"  material = elastic }}
tool ball = sphere {{ center = (0, 0, {R})  radius = {R}
  motion {{ uz = ramp(0, -{DEPTH}) }} }}
contact block.top -> ball {{ method = penalty {{ kind = area  stiffness = {float(penalty)!r} }} }}
fix block.xsym {{ ux }}
fix block.ysym {{ uy }}
fix block.bottom {{ ux uy uz }}
step press {{
  time = 0 .. 1
  increments = {steps}
  newton {{ tol = 1e-10  tol_displacement = 1e-10 }}
}}
output {{ fields = [displacement, contact] }}
"""


def hertz():
    """Half-space Hertz force of the quarter and peak pressure at d."""
    es = E / (1 - NU**2)
    a = math.sqrt(R * DEPTH)
    p = 4.0 / 3.0 * es * math.sqrt(R) * DEPTH**1.5
    return p / 4.0, 3.0 * p / (2.0 * math.pi * a * a)


def ctc_result(d):
    """Iterations, loop time (engine total less output), process CPU and
    peak RSS, total contact force and axis pressure of a `ctc run`
    directory."""
    import csv
    import glob

    with open(os.path.join(d, "summary.json")) as f:
        s = json.load(f)
    last = sorted(glob.glob(os.path.join(d, "contact_0_*.csv")))[-1]
    with open(last) as f:
        rows = list(csv.DictReader(f))
    axis = min(rows, key=lambda r: float(r["x"]) ** 2 + float(r["y"]) ** 2)
    t = s["timings"]
    out = {
        "free_dofs": s["free_dofs"],
        "iterations_per_increment": [i["iterations"] for i in s["increments"]],
        "newton_iterations": s["newton_iterations"],
        "wall_time": t["total"] - t["output"],
        "contact_force": -sum(float(r["force_z"]) for r in rows),
        "peak_pressure": float(axis["pressure"]),
        "linear_solver": f"{s['linear_solver']} ({s['ldlt_factorizations']} ldlt + "
        f"{s['cholesky_factorizations']} cholesky + {s['lu_factorizations']} lu, "
        f"{s.get('low_rank_updates', 0)} low-rank updates)",
        "factorization": t["factorization"],
        "timings": t,
        "threads": s.get("threads", 1),
    }
    out.update(process(d))
    return out


def process(d):
    """Process wall, CPU (user + sys) and peak RSS from /usr/bin/time."""
    with open(os.path.join(d, "time.txt")) as f:
        wall, user, sys_, rss = f.read().split()[:4]
    return {"process_wall": float(wall), "cpu_time": float(user) + float(sys_), "peak_rss_mib": int(rss) / 1024}


def all_runs(rs, key):
    return " ".join(f"{r[key]:.2f}" for r in rs)


def table(directory):
    import glob

    def runs(prefix, read):
        return [read(d) for d in sorted(glob.glob(os.path.join(directory, prefix + "_*")))]

    def fx_result(d):
        r = json.load(open(os.path.join(d, "fenicsx.json")))
        r["loop_cpu"] = r["cpu_time"]
        r.update(process(d))
        return r

    ctc = runs("ctc", ctc_result)
    fx = runs("fx", fx_result)
    if not ctc or not fx:
        raise SystemExit(f"no runs in {directory}")
    if {r["free_dofs"] for r in ctc} != {r["free_dofs"] for r in fx}:
        raise SystemExit("ctc and FEniCSx solved different numbers of free dofs")
    mesh = json.load(open(os.path.join(directory, "mesh.json")))
    print(f"N = {mesh['n']}: {mesh['nodes']} nodes, {mesh['tets']} tetrahedra, {mesh['free_dofs']} free dofs, "
          f"h_min = {mesh['h_min']:.4g}, penalty 10 E / h_min = {mesh['penalty']:.4g}")
    print()
    print("| code | Newton its | per increment | loop wall, min [s] | all runs [s] | process CPU, min [s] "
          "| all runs [s] | loop CPU, min [s] | peak RSS, max [MiB] | linear solver | loop wall / ctc "
          "| process CPU / ctc | its / ctc |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    base = min(r["wall_time"] for r in ctc)
    base_cpu = min(r["cpu_time"] for r in ctc)
    base_its = ctc[0]["newton_iterations"]
    for name, rs in (("ctc", ctc), (f"DOLFINx {fx[0]['dolfinx']}", fx)):
        best = min(rs, key=lambda r: r["wall_time"])
        cpu = min(r["cpu_time"] for r in rs)
        loop_cpu = f"{min(r['loop_cpu'] for r in rs):.2f}" if "loop_cpu" in best else "-"
        print(
            f"| {name} | {best['newton_iterations']} | {best['iterations_per_increment']} "
            f"| {best['wall_time']:.2f} | {all_runs(rs, 'wall_time')} | {cpu:.2f} "
            f"| {all_runs(rs, 'cpu_time')} | {loop_cpu} "
            f"| {max(r['peak_rss_mib'] for r in rs):.0f} | {best['linear_solver']} "
            f"| {best['wall_time'] / base:.2f} | {cpu / base_cpu:.2f} | {best['newton_iterations'] / base_its:.2f} |"
        )
    f_h, p_h = hertz()
    print()
    print("| quantity | ctc | DOLFINx | rel. diff | Hertz (half-space) | ctc / Hertz | DOLFINx / Hertz |")
    print("|---|---|---|---|---|---|---|")
    for q, h in (("contact_force", f_h), ("peak_pressure", p_h)):
        a, b = ctc[0][q], fx[0][q]
        print(f"| {q.replace('_', ' ')} | {a:.6g} | {b:.6g} | {abs(a - b) / abs(b):.1e} | {h:.6g} "
              f"| {a / h:.4f} | {b / h:.4f} |")
    same = all(r["contact_force"] == ctc[0]["contact_force"] for r in ctc)
    print()
    t = min(ctc, key=lambda r: r["wall_time"])["timings"]
    phases = ["setup", "assembly", "contact", "symbolic", "factorization", "low_rank", "solve", "residual"]
    its = base_its
    print(
        "ctc phases of its fastest run [s]: " + ", ".join(f"{p} {t.get(p, 0.0):.2f}" for p in phases)
        + f", output {t['output']:.2f} (not in the loop); symbolic and low_rank are parts of factorization; "
        f"{t['factorization'] / its:.2f} s of factorization per iteration; {ctc[0]['threads']} thread(s); "
        f"ctc's force identical in all runs: {same}."
    )
    fx_loop_cpu = min(r["loop_cpu"] for r in fx)
    fx_its = fx[0]["newton_iterations"]
    print()
    print(
        f"CPU ratio (the reliable figure under load): DOLFINx loop CPU {fx_loop_cpu:.2f} s / ctc process CPU "
        f"{base_cpu:.2f} s = {fx_loop_cpu / base_cpu:.2f} (ctc's whole process: mesh reading and output "
        f"included); per Newton iteration DOLFINx {fx_loop_cpu / fx_its:.3f} s CPU, ctc {base_cpu / base_its:.3f} s; "
        f"peak RSS ctc {max(r['peak_rss_mib'] for r in ctc):.0f} MiB, DOLFINx {max(r['peak_rss_mib'] for r in fx):.0f} MiB "
        f"(whole processes)."
    )


def solve(x, cells, faces, n, out, steps, pen, stop_after):
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

    domain = ufl.Mesh(basix.ufl.element("Lagrange", "tetrahedron", 1, shape=(3,)))
    m = dolfinx.mesh.create_mesh(MPI.COMM_SELF, cells, domain, x)
    V = dolfinx.fem.functionspace(m, ("Lagrange", 1, (3,)))
    mu = E / (2 * (1 + NU))
    lmbda = E * NU / ((1 + NU) * (1 - 2 * NU))

    def eps(w):
        return ufl.sym(ufl.grad(w))

    def sigma(w):
        return lmbda * ufl.tr(eps(w)) * ufl.Identity(3) + 2 * mu * eps(w)

    def ppos(z):
        return (z + abs(z)) / 2

    fdim = 2
    m.topology.create_connectivity(fdim, 3)

    def on(axis, value):
        return dolfinx.mesh.locate_entities_boundary(m, fdim, lambda p: np.isclose(p[axis], value))

    bottom, top, xsym, ysym = on(2, -L), on(2, 0.0), on(0, 0.0), on(1, 0.0)
    tags = dolfinx.mesh.meshtags(m, fdim, np.sort(top), np.full(len(top), 1, dtype=np.int32))
    zero = PETSc.ScalarType(0.0)
    bcs = [
        dolfinx.fem.dirichletbc(np.zeros(3, dtype=PETSc.ScalarType), dolfinx.fem.locate_dofs_topological(V, fdim, bottom), V),
        dolfinx.fem.dirichletbc(zero, dolfinx.fem.locate_dofs_topological(V.sub(0), fdim, xsym), V.sub(0)),
        dolfinx.fem.dirichletbc(zero, dolfinx.fem.locate_dofs_topological(V.sub(1), fdim, ysym), V.sub(1)),
    ]
    ds = ufl.Measure("ds", domain=m, subdomain_data=tags, metadata={"quadrature_degree": 2})
    u = dolfinx.fem.Function(V)
    v = ufl.TestFunction(V)
    d = dolfinx.fem.Constant(m, PETSc.ScalarType(0.0))
    xs = ufl.SpatialCoordinate(m)
    obstacle = R - d - ufl.sqrt(ufl.max_value(R**2 - xs[0] ** 2 - xs[1] ** 2, 0.0))
    penetration = ppos(u[2] - obstacle)
    F = ufl.inner(sigma(u), eps(v)) * ufl.dx + pen * penetration * v[2] * ds(1)
    opts = {
        "snes_type": "newtonls",
        "snes_linesearch_type": "basic",
        "snes_rtol": 1e-10,
        "snes_atol": 1e-10,
        "ksp_type": "preonly",
        "pc_type": "lu",
        "pc_factor_mat_solver_type": "mumps",
    }
    problem = dolfinx.fem.petsc.NonlinearProblem(F, u, bcs=bcs, petsc_options=opts, petsc_options_prefix="sphere_")
    snes = problem.solver
    its = []
    wall0, cpu0 = time.perf_counter(), time.process_time()
    for k in range(1, min(steps, stop_after) + 1):
        d.value = DEPTH * k / steps
        problem.solve()
        reason = snes.getConvergedReason()
        if reason <= 0:
            raise SystemExit(f"SNES diverged at step {k} (reason {reason})")
        its.append(int(snes.getIterationNumber()))
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    force = dolfinx.fem.assemble_scalar(dolfinx.fem.form(pen * penetration * ds(1)))
    # peak pressure: the axis vertex's consistent force over its tributary
    # area (int p N_i / int N_i), the analogue of ctc's nodal pressure
    Q = dolfinx.fem.functionspace(m, ("Lagrange", 1))
    w = ufl.TestFunction(Q)
    fp = dolfinx.fem.assemble_vector(dolfinx.fem.form(pen * penetration * w * ds(1))).array
    fl = dolfinx.fem.assemble_vector(dolfinx.fem.form(w * ds(1))).array
    xq = Q.tabulate_dof_coordinates()
    axis = int(np.argmin(np.sum(xq**2, axis=1)))
    ksp = snes.getKSP()
    mumps = ksp.getPC().getFactorMatrix()
    try:
        ordering = {0: "AMD", 2: "AMF", 3: "SCOTCH", 4: "PORD", 5: "METIS", 6: "QAMD", 7: "auto"}.get(
            mumps.getMumpsInfog(7), str(mumps.getMumpsInfog(7)))
        entries = mumps.getMumpsInfog(29)
    except Exception:  # noqa: BLE001 (older petsc4py)
        ordering, entries = "?", 0
    result = {
        "dolfinx": dolfinx.__version__,
        "free_dofs": V.dofmap.index_map.size_local * 3 - len(np.unique(np.concatenate([b.dof_indices()[0] for b in bcs]))),
        "h_min": float(np.min(np.diff(graded(n)))),
        "penalty": pen,
        "iterations_per_increment": its,
        "steps_solved": len(its),
        "newton_iterations": int(sum(its)),
        "wall_time": wall,
        "cpu_time": cpu,
        "timings_per_iteration": wall / max(1, sum(its)),
        "contact_force": float(force),
        "peak_pressure": float(fp[axis] / fl[axis]),
        "linear_solver": f"mumps lu ({ordering}, {entries} factor entries)",
    }
    with open(os.path.join(out, "fenicsx.json"), "w") as f:
        json.dump(result, f, indent=1)
    print(json.dumps(result))


def main():
    import sys

    if len(sys.argv) == 3 and sys.argv[1] == "--table":
        table(sys.argv[2])
        return
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--n", type=int, default=40, help="cubes per direction (40: ~200k free dofs)")
    ap.add_argument("--steps", type=int, default=4)
    ap.add_argument("--export-only", action="store_true")
    ap.add_argument("--stop-after", type=int, default=10**9,
                    help="solve only the first K steps (a per-iteration cost where a whole run is too long)")
    args = ap.parse_args()
    if args.n < 1:
        raise SystemExit("--n must be at least 1")
    os.makedirs(args.out, exist_ok=True)
    x, cells = box_mesh(args.n)
    faces = boundary_triangles(args.n)
    # the shortest edge: the first spacing of the graded axes (diagonals are longer)
    h_min = float(np.min(np.diff(graded(args.n))))
    pen = 10.0 * E / h_min
    if args.export_only:
        msh = os.path.join(args.out, "sphere3d.msh")
        write_gmsh(x, cells, faces, msh)
        with open(os.path.join(args.out, "sphere3d.ctc"), "w") as f:
            f.write(ctc_deck(msh, pen, args.steps))
        info = {"n": args.n, "nodes": len(x), "tets": len(cells), "free_dofs": free_dofs(args.n),
                "h_min": h_min, "penalty": pen}
        with open(os.path.join(args.out, "mesh.json"), "w") as f:
            json.dump(info, f, indent=1)
        return
    solve(x, cells, faces, args.n, args.out, args.steps, pen, args.stop_after)


if __name__ == "__main__":
    main()
