#!/usr/bin/env python3
"""Timed FEniCSx (DOLFINx 0.5) solves of a ctc problem export, for the speed
and Newton-iteration comparison of `speed.sh` (see SPEED.md).

`solve.py` is built for exactness (SciPy spsolve, Python contact loops);
this script solves the same exported problem the way a FEniCSx user would,
with PETSc linear algebra and a direct solver (MUMPS LU when PETSc has it,
else PETSc's own LU), and times the increment loop.

Variant A, "same discretization as ctc": nodal penalty at the slave nodes
  (alpha_i = k w_i, tributary weights w_i assembled by DOLFINx), exact gap to
  the circle or plane, consistent contact tangent alpha (n n^T + g Hess g);
  the elastic Jacobian is assembled by `dolfinx.fem.petsc.assemble_matrix`
  into a preallocated PETSc matrix (Dirichlet rows/columns by `bcs`), the
  nodal contact blocks added with `setValuesBlocked(ADD)`; the right-hand side
  gets the Dirichlet increments by `apply_lifting` / `set_bc`; KSP `preonly`
  + `lu`. Newton with ctc's convergence test (engine/src/solve/newton.rs):
  after each update, ||r_free|| / max(||f_ext + f_c|| + ||reactions||,
  ||f_int||) <= tol AND ||du|| / ||u|| <= tol_displacement, the latter
  replaced, when it fails while the residual passes, by the next correction
  computed with the factorization at hand (one back-substitution). No line
  search (ctc has one; it is reported whether ctc used it: it cannot be seen
  from outside, so iteration counts are what they are).

Variant B, "tutorial formulation" (J. Bleyer, comet-fenicsx, "Hertzian
  contact with a rigid indenter using a penalty approach", adapted to 2D and
  to the exact circle): the penalty term integrated on the contact facets at
  quadrature points, `pen * ppos(-g(u)) * dot(n(u), v) * ds` with
  `ppos(x) = (x + abs(x)) / 2`, g(u) = |x + u - c| - R, the Jacobian by
  `ufl.derivative`, `NonlinearProblem` + `NewtonSolver` (residual criterion,
  rtol = the deck's tol relative to the increment's first residual), KSP
  `preonly` + `lu`. Same mesh, same penalty value (the area penalty k is a
  pressure per unit gap, which is what `pen` is).

Timed: `wall_time`, the increment loop only (setup, meshes, FFCx JIT, facet
tags and weights excluded, like `ctc bench`'s solve time excludes its deck
compilation). Split (A): assembly (elastic residual and Jacobian, lifting),
contact (gaps, forces, tangent blocks), factorization (`KSP.setUp`: the
numeric LU; the first one also does the symbolic analysis), solve (the
triangular solves). Split (B): residual and Jacobian callbacks; the rest of
NewtonSolver (factorization, solve, updates) as `linear_and_rest`.

Usage: speed.py PROBLEM.json OUT.json --variant A|B [--lu mumps|petsc]
                 [--ds-degree 2]
                 [--factor lu|cholesky]   (A only)
       speed.py --table DIR    (the comparison table of the runs speed.sh
                                left in DIR: ctc_<rep>.json, A_<rep>.json,
                                B_<rep>.json, load.txt)
"""

import argparse
import json
import os
import sys
import time

import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem
import dolfinx.fem.petsc
import dolfinx.mesh
import dolfinx.nls.petsc

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from solve import build_mesh, facet_tags, function_space_map, node_maps  # noqa: E402

# MUMPS INFOG(7): the ordering effectively used.
MUMPS_ORDERINGS = {0: "AMD", 1: "user", 2: "AMF", 3: "SCOTCH", 4: "PORD", 5: "METIS", 6: "QAMD"}


def lu_solver(ksp, package, factor="lu"):
    """KSP preonly + `factor` (lu, or cholesky: MUMPS symmetric L D L^T, which
    accepts indefinite matrices) with `package`; falls back to PETSc's LU if
    the package is not available. Returns the package in use."""
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType(factor)
    try:
        pc.setFactorSolverType(package)
        # Probe on a 1x1 matrix: setFactorSolverType does not check.
        probe = PETSc.Mat().createAIJ([1, 1], comm=MPI.COMM_SELF)
        probe.setUp()
        probe.setValue(0, 0, 1.0)
        probe.assemble()
        k = PETSc.KSP().create(MPI.COMM_SELF)
        k.setType("preonly")
        k.getPC().setType("lu")
        k.getPC().setFactorSolverType(package)
        k.setOperators(probe)
        k.setUp()
        k.destroy()
        probe.destroy()
    except PETSc.Error:
        package = "petsc"
        pc.setType("lu")
        pc.setFactorSolverType(package)
    return package


def mumps_ordering(ksp, package):
    if package != "mumps":
        return None
    try:
        info = ksp.getPC().getFactorMatrix().getMumpsInfog(7)
        return MUMPS_ORDERINGS.get(int(info), str(info))
    except PETSc.Error:
        return None


class Setup:
    """Mesh, spaces, forms and maps shared by both variants."""

    def __init__(self, problem, ds_degree):
        self.problem = problem
        n_nodes = len(problem["nodes"])
        self.n_nodes = n_nodes
        mesh, kind = build_mesh(problem)
        self.mesh = mesh
        vertex, _ = node_maps(mesh, n_nodes)
        V = dolfinx.fem.VectorFunctionSpace(mesh, ("Lagrange", 1))
        self.V = V
        self.block = function_space_map(mesh, V, n_nodes)
        self.n_dofs = V.dofmap.index_map.size_local * V.dofmap.index_map_bs
        self.axi = problem["analysis"] == "axisymmetric"
        x = ufl.SpatialCoordinate(mesh)
        self.x = x
        self.measure = 2.0 * np.pi * x[0] if self.axi else problem["thickness"]
        E, nu = problem["young"], problem["poisson"]
        lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
        mu = E / (2.0 * (1.0 + nu))
        axi = self.axi

        def eps(w):
            if axi:
                return ufl.as_tensor(
                    [
                        [w[0].dx(0), 0.5 * (w[0].dx(1) + w[1].dx(0)), 0.0],
                        [0.5 * (w[0].dx(1) + w[1].dx(0)), w[1].dx(1), 0.0],
                        [0.0, 0.0, w[0] / x[0]],
                    ]
                )
            return ufl.sym(ufl.grad(w))

        def sigma(w):
            e = eps(w)
            return lam * ufl.tr(e) * ufl.Identity(3 if axi else 2) + 2.0 * mu * e

        self.eps, self.sigma = eps, sigma
        self.dx = ufl.dx(metadata={"quadrature_degree": 1 if kind == "tri3" else 2})
        groups = [p["edges"] for p in problem["pressure"]] + [c["edges"] for c in problem["contacts"]]
        self.n_pressure = len(problem["pressure"])
        tags = facet_tags(mesh, vertex, groups) if groups else None
        self.ds = ufl.Measure(
            "ds", domain=mesh, subdomain_data=tags, metadata={"quadrature_degree": ds_degree}
        )
        self.u = dolfinx.fem.Function(V)
        self.v = ufl.TestFunction(V)
        self.du = ufl.TrialFunction(V)
        # Dirichlet conditions: one per (node set, component), on V.sub(c),
        # with a Constant updated per increment.
        self.bc_values = []
        self.bcs = []
        constrained = np.zeros(self.n_dofs, dtype=bool)
        for d in problem["dirichlet"]:
            c = d["component"]
            dofs = (2 * self.block[np.array(d["nodes"])] + c).astype(np.int32)
            value = dolfinx.fem.Constant(mesh, PETSc.ScalarType(0.0))
            self.bc_values.append((value, d["values"]))
            self.bcs.append(dolfinx.fem.dirichletbc(value, np.sort(dofs), V.sub(c)))
            constrained[dofs] = True
        self.constrained = constrained
        self.free = np.flatnonzero(~constrained)

    def set_increment_bcs(self, k):
        for value, values in self.bc_values:
            value.value = values[k]

    def axis_node(self, contact):
        """Slave node on x = 0 (where ctc reads the peak pressure)."""
        X = np.array(self.problem["nodes"])
        nodes = np.array(contact["nodes"])
        span = max(np.ptp(X[:, 0]), 1.0)
        hits = nodes[np.abs(X[nodes, 0]) <= 1e-9 * span]
        return int(hits[0]) if len(hits) else None


def tool_gap(contact, k, xn):
    """Gap, unit normal and gap Hessian factor of points xn (m x 2) to the
    tool of `contact` at increment k (vectorized)."""
    tr = np.array(contact["translation"][k])
    if contact["tool"] == "circle":
        d = xn - (np.array(contact["point"]) + tr)
        dist = np.linalg.norm(d, axis=1)
        return dist - contact["radius"], d / dist[:, None], dist
    nrm = np.array(contact["normal"])
    g = (xn - (np.array(contact["point"]) + tr)) @ nrm
    return g, np.tile(nrm, (len(xn), 1)), None


def solve_a(setup, package, factor="lu"):
    """Variant A: ctc's nodal discretization on DOLFINx/PETSc machinery."""
    problem, V, u, v, du = setup.problem, setup.V, setup.u, setup.v, setup.du
    sigma, eps, dx, ds, measure = setup.sigma, setup.eps, setup.dx, setup.ds, setup.measure
    f_int_form = dolfinx.fem.form(ufl.inner(sigma(u), eps(v)) * measure * dx)
    jac_form = dolfinx.fem.form(ufl.inner(sigma(du), eps(v)) * measure * dx)
    n = ufl.FacetNormal(setup.mesh)
    unit_pressure = []
    for i in range(setup.n_pressure):
        vec = dolfinx.fem.petsc.assemble_vector(dolfinx.fem.form(-ufl.dot(n, v) * measure * ds(i + 1)))
        unit_pressure.append(vec.getArray().copy())
    S = dolfinx.fem.FunctionSpace(setup.mesh, ("Lagrange", 1))
    sblock = function_space_map(setup.mesh, S, setup.n_nodes)
    q = ufl.TestFunction(S)
    contacts = []
    for i, c in enumerate(problem["contacts"]):
        w_all = dolfinx.fem.petsc.assemble_vector(
            dolfinx.fem.form(q * measure * ds(setup.n_pressure + i + 1))
        ).getArray()
        nodes = np.array(c["nodes"])
        w = w_all[sblock[nodes]]
        alpha = c["stiffness"] * w if c["penalty_kind"] == "area" else np.full(len(w), c["stiffness"])
        blocks = setup.block[nodes]
        # a constrained slave dof keeps its identity row: no contact there
        keep = ~(setup.constrained[2 * blocks] | setup.constrained[2 * blocks + 1])
        contacts.append((c, nodes, blocks, alpha, keep))
    X = np.zeros((V.dofmap.index_map.size_local, 2))
    X[setup.block] = np.array(problem["nodes"])

    A = dolfinx.fem.petsc.create_matrix(jac_form)
    b = dolfinx.fem.petsc.create_vector(f_int_form)
    fvec = dolfinx.fem.petsc.create_vector(f_int_form)
    dx_vec = dolfinx.fem.petsc.create_vector(f_int_form)
    x_vec = u.vector
    ksp = PETSc.KSP().create(MPI.COMM_SELF)
    ksp.setOperators(A)
    package = lu_solver(ksp, package, factor)
    factor = ksp.getPC().getType()
    ksp.setFromOptions()

    tol = problem["newton_tol"]
    tol_du = problem.get("newton_tol_displacement", tol)
    max_iter = problem["newton_max_iter"]
    constrained, free = setup.constrained, setup.free
    timers = {"assembly": 0.0, "contact": 0.0, "factorization": 0.0, "solve": 0.0}
    state = {"f_c": None, "blocks": []}
    factor_times = []

    def contact_terms(k):
        """Nodal contact forces (DOLFINx dof order) and 2x2 tangent blocks."""
        t0 = time.perf_counter()
        uu = u.x.array.reshape(-1, 2)
        f_c = np.zeros(setup.n_dofs)
        blocks = []
        for c, nodes, bl, alpha, keep in contacts:
            g, nrm, dist = tool_gap(c, k, X[bl] + uu[bl])
            active = (g < 0.0) & keep
            a, g, nrm = alpha[active], g[active], nrm[active]
            f = -(a * g)[:, None] * nrm
            f_c[2 * bl[active]] += f[:, 0]
            f_c[2 * bl[active] + 1] += f[:, 1]
            nn = nrm[:, :, None] * nrm[:, None, :]
            kk = nn.copy()
            if dist is not None:
                kk += (g / dist[active])[:, None, None] * (np.eye(2)[None] - nn)
            kk *= a[:, None, None]
            blocks.append((bl[active], kk))
        timers["contact"] += time.perf_counter() - t0
        return f_c, blocks

    def residual(k, f_ext):
        """r = f_int - f_ext - f_c (numpy) and ctc's relative residual."""
        t0 = time.perf_counter()
        with fvec.localForm() as loc:
            loc.set(0.0)
        dolfinx.fem.petsc.assemble_vector(fvec, f_int_form)
        f_int = fvec.getArray()
        timers["assembly"] += time.perf_counter() - t0
        f_c, blocks = contact_terms(k)
        state["f_c"], state["blocks"] = f_c, blocks
        r = f_int - f_ext - f_c
        reactions = np.where(constrained, r, 0.0)
        ref = max(np.linalg.norm(f_ext + f_c) + np.linalg.norm(reactions), np.linalg.norm(f_int), 1e-300)
        return r, np.linalg.norm(r[free]) / ref

    def rhs(r, lift):
        """b = -r on free dofs, Dirichlet increments by lifting / set_bc."""
        b.setArray(-r)
        if lift:
            dolfinx.fem.petsc.apply_lifting(b, [jac_form], bcs=[setup.bcs], x0=[x_vec], scale=1.0)
        dolfinx.fem.petsc.set_bc(b, setup.bcs, x_vec, 1.0)

    def jacobian():
        t0 = time.perf_counter()
        A.zeroEntries()
        dolfinx.fem.petsc.assemble_matrix(A, jac_form, bcs=setup.bcs)
        A.assemblyBegin(PETSc.Mat.AssemblyType.FLUSH)
        A.assemblyEnd(PETSc.Mat.AssemblyType.FLUSH)
        timers["assembly"] += time.perf_counter() - t0
        t0 = time.perf_counter()
        for bl, kk in state["blocks"]:
            for j in range(len(bl)):
                A.setValuesBlocked(int(bl[j]), int(bl[j]), kk[j], addv=PETSc.InsertMode.ADD_VALUES)
        timers["contact"] += time.perf_counter() - t0
        t0 = time.perf_counter()
        A.assemble()
        timers["assembly"] += time.perf_counter() - t0

    def factor_solve():
        t0 = time.perf_counter()
        ksp.setOperators(A)
        ksp.setUp()
        t1 = time.perf_counter()
        ksp.solve(b, dx_vec)
        t2 = time.perf_counter()
        timers["factorization"] += t1 - t0
        timers["solve"] += t2 - t1
        factor_times.append(t1 - t0)

    iterations, residuals = [], []
    c_loop = time.process_time()
    t_loop = time.perf_counter()
    for k, _t in enumerate(problem["times"]):
        f_ext = np.zeros(setup.n_dofs)
        for i, p in enumerate(problem["pressure"]):
            f_ext += p["values"][k] * unit_pressure[i]
        setup.set_increment_bcs(k)
        r, rel = residual(k, f_ext)
        history = []
        count = 0
        while True:
            if count >= max_iter:
                raise RuntimeError(f"variant A, increment {k + 1}: no convergence in {max_iter} iterations")
            jacobian()
            rhs(r, lift=True)
            factor_solve()
            step = dx_vec.getArray()
            u.x.array[:] += step
            u.x.scatter_forward()
            count += 1
            du_norm = np.linalg.norm(step)
            r, rel = residual(k, f_ext)
            history.append(float(rel))
            if rel <= tol:
                u_norm = max(np.linalg.norm(u.x.array), 1e-300)
                if du_norm / u_norm <= tol_du:
                    break
                # next correction with the factorization at hand
                rhs(r, lift=False)
                t0 = time.perf_counter()
                ksp.solve(b, dx_vec)
                timers["solve"] += time.perf_counter() - t0
                if np.linalg.norm(dx_vec.getArray()) / u_norm <= tol_du:
                    break
        iterations.append(count)
        residuals.append(history)
    wall = time.perf_counter() - t_loop
    cpu = time.process_time() - c_loop
    ordering = mumps_ordering(ksp, package)

    uu = u.x.array.reshape(-1, 2)
    forces, peaks = [], []
    for (c, nodes, bl, alpha, keep) in contacts:
        f = state["f_c"].reshape(-1, 2)[bl]
        forces.append(f.sum(axis=0).tolist())
        axis = setup.axis_node(c)
        if axis is None:
            peaks.append(None)
            continue
        j = int(np.flatnonzero(nodes == axis)[0])
        g, _, _ = tool_gap(c, len(problem["times"]) - 1, (X[bl[j]] + uu[bl[j]])[None])
        p = -c["stiffness"] * g[0] if c["penalty_kind"] == "area" else -alpha[j] * g[0] / c["tributary"][j]
        peaks.append(float(max(p, 0.0)))
    return {
        "variant": "A",
        "package": package,
        "factor": factor,
        "ordering": ordering,
        "newton_iterations": iterations,
        "residuals": residuals,
        "wall_time": wall,
        "cpu_time": cpu,
        "timings": timers,
        "factorization_times": factor_times,
        "total_contact_force": forces,
        "peak_pressure": peaks,
    }


def solve_b(setup, package):
    """Variant B: the tutorial's quadrature-point penalty with NewtonSolver."""
    problem, V, u, v = setup.problem, setup.V, setup.u, setup.v
    sigma, eps, dx, ds, measure, x = setup.sigma, setup.eps, setup.dx, setup.ds, setup.measure, setup.x
    mesh = setup.mesh
    n_f = ufl.FacetNormal(mesh)

    def ppos(z):
        return (z + abs(z)) / 2.0

    F = ufl.inner(sigma(u), eps(v)) * measure * dx
    pressures = []
    for i, p in enumerate(problem["pressure"]):
        pk = dolfinx.fem.Constant(mesh, PETSc.ScalarType(0.0))
        pressures.append((pk, p["values"]))
        F += pk * ufl.dot(n_f, v) * measure * ds(i + 1)
    tools = []
    contact_forms = []
    for i, c in enumerate(problem["contacts"]):
        centre = dolfinx.fem.Constant(mesh, np.array(c["point"], dtype=PETSc.ScalarType))
        tools.append((centre, c))
        pen = dolfinx.fem.Constant(mesh, PETSc.ScalarType(c["stiffness"]))
        if c["penalty_kind"] != "area":
            raise ValueError("variant B needs an area penalty (a pressure per unit gap)")
        if c["tool"] == "circle":
            d = x + u - centre
            dist = ufl.sqrt(ufl.dot(d, d))
            gap = dist - c["radius"]
            nrm = d / dist
        else:
            nrm = ufl.as_vector(c["normal"])
            gap = ufl.dot(x + u - centre, nrm)
        fc = pen * ppos(-gap) * ufl.dot(nrm, v) * measure * ds(setup.n_pressure + i + 1)
        F -= fc
        contact_forms.append((dolfinx.fem.form(fc), pen, gap, c))

    timers = {"residual": 0.0, "jacobian": 0.0}
    history = [[]]  # ||F|| at every residual evaluation, per increment

    class TimedProblem(dolfinx.fem.petsc.NonlinearProblem):
        def F(self, xv, bv):
            t0 = time.perf_counter()
            super().F(xv, bv)
            history[-1].append(bv.norm())
            timers["residual"] += time.perf_counter() - t0

        def J(self, xv, Av):
            t0 = time.perf_counter()
            super().J(xv, Av)
            timers["jacobian"] += time.perf_counter() - t0

    nlp = TimedProblem(F, u, bcs=setup.bcs)
    solver = dolfinx.nls.petsc.NewtonSolver(MPI.COMM_SELF, nlp)
    solver.convergence_criterion = "residual"
    solver.rtol = problem["newton_tol"]
    solver.atol = 1e-14
    solver.max_it = problem["newton_max_iter"]
    solver.report = False
    solver.error_on_nonconvergence = True
    ksp = solver.krylov_solver
    package = lu_solver(ksp, package)

    iterations = []
    c_loop = time.process_time()
    t_loop = time.perf_counter()
    for k, _t in enumerate(problem["times"]):
        setup.set_increment_bcs(k)
        for pk, values in pressures:
            pk.value = values[k]
        for centre, c in tools:
            centre.value = np.array(c["point"]) + np.array(c["translation"][k])
        n_it, converged = solver.solve(u)
        if not converged:
            raise RuntimeError(f"variant B, increment {k + 1}: no convergence")
        iterations.append(int(n_it))
        history.append([])
    wall = time.perf_counter() - t_loop
    cpu = time.process_time() - c_loop
    ordering = mumps_ordering(ksp, package)

    # Peak pressure: the axis node's contact force over its tributary weight,
    # int p N_i / int N_i (what ctc's nodal pressure is); the pointwise
    # -pen g at the vertex is lower by about pen h^2 / (8 R), the chord-to-arc
    # sagitta, since the quadrature points between vertices penetrate more.
    forces, peaks, vertex_peaks = [], [], []
    X = np.array(problem["nodes"])
    uu = u.x.array.reshape(-1, 2)
    for form, pen, _gap, c in contact_forms:
        vec = dolfinx.fem.petsc.assemble_vector(form)
        arr = vec.getArray()
        forces.append([float(arr[0::2].sum()), float(arr[1::2].sum())])
        axis = setup.axis_node(c)
        if axis is None:
            peaks.append(None)
            vertex_peaks.append(None)
            continue
        bl = setup.block[axis]
        j = int(np.flatnonzero(np.array(c["nodes"]) == axis)[0])
        peaks.append(float(np.hypot(arr[2 * bl], arr[2 * bl + 1]) / c["tributary"][j]))
        tr = np.array(c["translation"][-1])
        xn = X[axis] + uu[bl]
        if c["tool"] == "circle":
            g = np.linalg.norm(xn - np.array(c["point"]) - tr) - c["radius"]
        else:
            g = float(np.dot(xn - np.array(c["point"]) - tr, c["normal"]))
        vertex_peaks.append(float(max(-c["stiffness"] * g, 0.0)))
    return {
        "variant": "B",
        "package": package,
        "ordering": ordering,
        "newton_iterations": iterations,
        "wall_time": wall,
        "cpu_time": cpu,
        "timings": {**timers, "linear_and_rest": wall - timers["residual"] - timers["jacobian"]},
        "total_contact_force": forces,
        "peak_pressure": peaks,
        "peak_pressure_vertex": vertex_peaks,
        "residual_norms": history[:-1],
    }


def table(directory):
    """Min-of-repetitions table of ctc, A and B from speed.sh's run files."""
    import glob

    def runs(prefix):
        out = []
        for path in sorted(glob.glob(os.path.join(directory, f"{prefix}_*.json"))):
            with open(path) as fh:
                run = json.load(fh)
            cpu = path[: -len(".json")] + ".cpu"
            if os.path.exists(cpu):
                with open(cpu) as fh:
                    run["cpu_time"] = sum(float(w) for w in fh.read().split()[:2])
            out.append(run)
        if not out:
            sys.exit(f"{directory}: no {prefix}_*.json runs")
        return out

    ctc, a, b = runs("ctc"), runs("A"), runs("B")
    best_ctc = min(ctc, key=lambda r: r["wall_time"])
    best_a = min(a, key=lambda r: r["wall_time"])
    best_b = min(b, key=lambda r: r["wall_time"])
    its_ctc = best_ctc["newton_iterations"]
    acc = {v["quantity"]: v["computed"] for v in best_ctc["accuracy"]}
    f_ctc, p_ctc = acc["contact_force"], acc["peak_pressure"]
    if best_a["free_dofs"] != best_ctc["free_dofs"]:
        sys.exit(f"free dofs differ: ctc {best_ctc['free_dofs']}, FEniCSx {best_a['free_dofs']}")
    rows = [
        (
            "ctc bench",
            best_ctc["free_dofs"],
            its_ctc,
            best_ctc["iterations_per_increment"],
            [r["wall_time"] for r in ctc],
            min(r.get("cpu_time", float("nan")) for r in ctc),
            best_ctc["per_iteration"]["factorization"],
            best_ctc["linear_solver"] + " (ctc)",
        ),
    ]
    for name, runs_, best in (("FEniCSx A (nodal)", a, best_a), ("FEniCSx B (tutorial)", b, best_b)):
        its = best["newton_iterations"]
        fac = best["timings"].get("factorization")
        rows.append(
            (
                name,
                best["free_dofs"],
                sum(its),
                its,
                [r["wall_time"] for r in runs_],
                min(r.get("cpu_time", float("nan")) for r in runs_),
                None if fac is None else fac / sum(its),
                f"{best['package']} {best.get('factor', 'lu')} ({best['ordering']})",
            )
        )
    print(f"| code | free dofs | Newton its | per increment | loop wall, min of {len(ctc)} [s] | all runs [s] "
          "| CPU, min [s] | wall per iteration [ms] | factorization per it. [ms] | linear solver "
          "| wall / ctc | CPU / ctc | its / ctc |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    w_ctc, c_ctc = min(rows[0][4]), rows[0][5]
    for name, dofs, its, per, walls, cpu, fac, solver in rows:
        w = min(walls)
        print(
            f"| {name} | {dofs} | {its} | {per} | {w:.3f} | {' '.join(f'{x:.3f}' for x in walls)} "
            f"| {cpu:.3f} | {1e3 * w / its:.1f} | {'-' if fac is None else f'{1e3 * fac:.1f}'} | {solver} "
            f"| {w / w_ctc:.2f} | {cpu / c_ctc:.2f} | {its / its_ctc:.2f} |"
        )
    print()
    print("CPU: FEniCSx = process CPU time of the increment loop; ctc = user + sys of the whole "
          "`ctc bench` process (deck compilation and Hertz post-processing included), so CPU / ctc "
          "is a lower bound of the loop's ratio.")
    print()
    print(f"ctc time split per iteration [ms]: " + ", ".join(
        f"{k} {1e3 * v:.1f}" for k, v in best_ctc["per_iteration"].items()
    ) + f"; loop / iteration {1e3 * best_ctc['wall_time'] / its_ctc:.1f}")
    ta = best_a["timings"]
    print("FEniCSx A time split per iteration [ms]: " + ", ".join(
        f"{k} {1e3 * v / sum(best_a['newton_iterations']):.1f}" for k, v in ta.items()
    ) + f"; first factorization (with analysis) {1e3 * best_a['factorization_times'][0]:.1f}")
    tb = best_b["timings"]
    print("FEniCSx B time split per iteration [ms]: " + ", ".join(
        f"{k} {1e3 * v / sum(best_b['newton_iterations']):.1f}" for k, v in tb.items()
    ))
    print()
    print(f"Agreement with ctc (final increment): total contact force F_y ctc {f_ctc:.10g}, peak pressure ctc {p_ctc:.10g}")
    for name, best in (("A", best_a), ("B", best_b)):
        f = best["total_contact_force"][0][1]
        p = best["peak_pressure"][0]
        print(f"  {name}: F_y {f:.10g} (rel diff {abs(f - f_ctc) / abs(f_ctc):.2e}), "
              f"peak {p:.10g} (rel diff {abs(p - p_ctc) / abs(p_ctc):.2e})"
              + (f", vertex -pen g {best['peak_pressure_vertex'][0]:.6g}" if "peak_pressure_vertex" in best else ""))


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--table":
        table(sys.argv[2])
        return
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("problem")
    ap.add_argument("out")
    ap.add_argument("--variant", choices=["A", "B"], required=True)
    ap.add_argument("--lu", default="mumps", help="PETSc LU package (mumps, or petsc)")
    ap.add_argument("--factor", choices=["lu", "cholesky"], default="lu",
                    help="variant A: LU, or MUMPS symmetric L D L^T (ctc factorizes L D L^T)")
    ap.add_argument("--ds-degree", type=int, default=2, help="quadrature degree on facets (B)")
    args = ap.parse_args()
    with open(args.problem) as fh:
        problem = json.load(fh)
    if problem.get("format") != "ctc-fenicsx-problem-1":
        sys.exit(f"{args.problem}: unknown format {problem.get('format')!r}")
    t0 = time.perf_counter()
    setup = Setup(problem, args.ds_degree)
    t_setup = time.perf_counter() - t0
    if args.variant == "A":
        result = solve_a(setup, args.lu, args.factor)
    else:
        result = solve_b(setup, args.lu)
    result.update(
        {
            "case": problem["case"],
            "dolfinx_version": dolfinx.__version__,
            "petsc_version": ".".join(str(i) for i in PETSc.Sys.getVersion()),
            "dofs": setup.n_dofs,
            "free_dofs": int(len(setup.free)),
            "setup_time": t_setup,
            "ds_degree": args.ds_degree,
        }
    )
    with open(args.out, "w") as fh:
        json.dump(result, fh, indent=1)
        fh.write("\n")
    its = result["newton_iterations"]
    print(
        f"{result['case']} variant {result['variant']}: {result['free_dofs']} free dofs,"
        f" {result.get('factor', 'lu')} {result['package']}"
        f" ({result['ordering']}), Newton {sum(its)} {its}, loop {result['wall_time']:.3f} s"
        f" ({1e3 * result['wall_time'] / max(sum(its), 1):.1f} ms/it), force {result['total_contact_force']},"
        f" peak {result['peak_pressure']}"
    )


if __name__ == "__main__":
    main()
