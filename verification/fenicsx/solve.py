#!/usr/bin/env python3
"""FEniCSx (DOLFINx 0.5) reference solver for ctc problem exports (issue 9).

Reads a problem written by ctc (`<case>.problem.json`: mesh with ctc's node
numbering, material, Dirichlet values and pressures per increment, penalty
contact pairs against rigid planes/circles) and solves it with DOLFINx on the
SAME mesh with the SAME discretization:

* P1 triangles / Q1 quadrilaterals, small-strain linear elasticity, plane
  strain (thickness t) or axisymmetric (x = r, measure 2 pi r dx, totals over
  2 pi); the quadrature rules of ctc's elements: 1 point (centroid) on
  triangles, 2x2 Gauss on quadrilaterals (`quadrature_degree` 1 and 2);
* pressure loads assembled by DOLFINx as `-p n . v` on tagged facets
  (`ds`, exact quadrature);
* penalty contact at the slave nodes ("vertex quadrature"): node i gets
  f_i = -alpha_i g_i grad g_i for g_i < 0, alpha_i = k w_i (area penalty)
  or k (nodal), where the tributary weight w_i = int_Gc N_i t ds (plane) or
  int_Gc N_i 2 pi r ds (axisymmetric) is ASSEMBLED BY DOLFINX from a P1
  test function on the tagged contact facets (and checked against ctc's);
  the gap is the exact distance to the tool: |x + u - c| - R for a circle
  (nonlinear in u), (x + u - p) . n for a plane; the consistent tangent
  alpha_i (grad g grad g^T + g Hess g) is added to DOLFINx's Jacobian;
* a Newton loop per increment (the increments of the ctc deck): the
  residual r = f_int(u) - f_ext - f_c(u) and the Jacobian of the elastic
  forms are assembled by DOLFINx (PETSc), the contact terms added nodally,
  Dirichlet dofs eliminated, the free system solved with SciPy's sparse LU.
  Converged when ||r_free|| / max(||f_ext + f_c|| + ||reactions||,
  ||f_int||) <= tol (ctc's residual criterion and the deck's tol).

Times: `wall_time` is the increment loop (assembly, contact, solves);
`setup_time` the mesh, forms (FFCx JIT compilation, cached between runs),
facet tags and tributary weights.

Usage: solve.py PROBLEM.json OUT.json
"""

import json
import sys
import time

import numpy as np
import scipy.sparse
import scipy.sparse.linalg
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem
import dolfinx.fem.petsc
import dolfinx.mesh


def build_mesh(problem):
    """DOLFINx mesh of the exported cells; returns (mesh, kind)."""
    nodes = np.array(problem["nodes"], dtype=np.float64)
    cells = np.array(problem["cells"], dtype=np.int64)
    kind = problem["cell_kind"]
    if kind == "quad4":
        # ctc: counter-clockwise a b c d; DOLFINx: tensor-product order a b d c.
        cells = cells[:, [0, 1, 3, 2]]
        cell = "quadrilateral"
    elif kind == "tri3":
        cell = "triangle"
    else:
        raise ValueError(f"unsupported cell kind {kind}")
    domain = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
    mesh = dolfinx.mesh.create_mesh(MPI.COMM_SELF, cells, nodes, domain)
    return mesh, kind


def node_maps(mesh, n_nodes):
    """ctc node -> DOLFINx vertex, and ctc node -> geometry row."""
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim, 0)
    c2v = mesh.topology.connectivity(tdim, 0)
    gdofmap = mesh.geometry.dofmap
    original = np.asarray(mesh.geometry.input_global_indices)
    vertex = np.full(n_nodes, -1, dtype=np.int64)
    geom = np.full(n_nodes, -1, dtype=np.int64)
    n_cells = mesh.topology.index_map(tdim).size_local
    for c in range(n_cells):
        for v, g in zip(c2v.links(c), gdofmap.links(c)):
            vertex[original[g]] = v
            geom[original[g]] = g
    if (vertex < 0).any():
        raise RuntimeError("some ctc nodes are not mesh vertices")
    return vertex, geom


def function_space_map(mesh, V, n_nodes):
    """ctc node -> block dof of the P1/Q1 space V (local dof i <-> vertex i)."""
    tdim = mesh.topology.dim
    gdofmap = mesh.geometry.dofmap
    original = np.asarray(mesh.geometry.input_global_indices)
    block = np.full(n_nodes, -1, dtype=np.int64)
    n_cells = mesh.topology.index_map(tdim).size_local
    for c in range(n_cells):
        for g, d in zip(gdofmap.links(c), V.dofmap.cell_dofs(c)):
            block[original[g]] = d
    if (block < 0).any():
        raise RuntimeError("some ctc nodes have no dof")
    return block


def facet_tags(mesh, vertex, edge_groups):
    """Meshtags of the boundary facets of each edge group (tag = index + 1)."""
    mesh.topology.create_connectivity(1, 0)
    f2v = mesh.topology.connectivity(1, 0)
    n_facets = mesh.topology.index_map(1).size_local
    lookup = {}
    for f in range(n_facets):
        lookup[frozenset(int(v) for v in f2v.links(f))] = f
    indices, values = [], []
    for tag, edges in enumerate(edge_groups, start=1):
        for a, b in edges:
            key = frozenset((int(vertex[a]), int(vertex[b])))
            if key not in lookup:
                raise RuntimeError(f"edge ({a}, {b}) is not a mesh facet")
            indices.append(lookup[key])
            values.append(tag)
    indices = np.array(indices, dtype=np.int32)
    values = np.array(values, dtype=np.int32)
    order = np.argsort(indices, kind="stable")
    return dolfinx.mesh.meshtags(mesh, 1, indices[order], values[order])


def petsc_to_scipy(mat):
    indptr, indices, data = mat.getValuesCSR()
    return scipy.sparse.csr_matrix((data, indices, indptr), shape=mat.getSize())


def assemble_vec(form):
    vec = dolfinx.fem.petsc.assemble_vector(form)
    vec.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    out = vec.getArray().copy()
    vec.destroy()
    return out


def solve(problem):
    t_start = time.perf_counter()
    n_nodes = len(problem["nodes"])
    mesh, kind = build_mesh(problem)
    vertex, _ = node_maps(mesh, n_nodes)
    V = dolfinx.fem.VectorFunctionSpace(mesh, ("Lagrange", 1))
    block = function_space_map(mesh, V, n_nodes)
    n_dofs = V.dofmap.index_map.size_local * V.dofmap.index_map_bs
    # ctc dof (2 node + c) -> DOLFINx dof
    dof = np.empty(2 * n_nodes, dtype=np.int64)
    dof[0::2] = 2 * block
    dof[1::2] = 2 * block + 1

    axi = problem["analysis"] == "axisymmetric"
    x = ufl.SpatialCoordinate(mesh)
    measure = 2.0 * np.pi * x[0] if axi else problem["thickness"]
    E, nu = problem["young"], problem["poisson"]
    lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    mu = E / (2.0 * (1.0 + nu))

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

    degree = 1 if kind == "tri3" else 2  # ctc: centroid / 2x2 Gauss
    dx = ufl.dx(metadata={"quadrature_degree": degree})
    u = dolfinx.fem.Function(V)
    v = ufl.TestFunction(V)
    du = ufl.TrialFunction(V)
    f_int_form = dolfinx.fem.form(ufl.inner(sigma(u), eps(v)) * measure * dx)
    jac_form = dolfinx.fem.form(ufl.inner(sigma(du), eps(v)) * measure * dx)

    # Facet tags: pressure groups first, then contact groups.
    groups = [p["edges"] for p in problem["pressure"]] + [
        c["edges"] for c in problem["contacts"]
    ]
    n_pressure = len(problem["pressure"])
    tags = facet_tags(mesh, vertex, groups) if groups else None
    ds = ufl.Measure("ds", domain=mesh, subdomain_data=tags, metadata={"quadrature_degree": 2})
    n = ufl.FacetNormal(mesh)
    unit_pressure = [
        assemble_vec(dolfinx.fem.form(-ufl.dot(n, v) * measure * ds(i + 1)))
        for i in range(n_pressure)
    ]

    # Tributary weights of the contact nodes, assembled by DOLFINx.
    S = dolfinx.fem.FunctionSpace(mesh, ("Lagrange", 1))
    sblock = function_space_map(mesh, S, n_nodes)
    q = ufl.TestFunction(S)
    contacts = []
    trib_rel = 0.0
    for i, c in enumerate(problem["contacts"]):
        w_all = assemble_vec(dolfinx.fem.form(q * measure * ds(n_pressure + i + 1)))
        w = np.array([w_all[sblock[node]] for node in c["nodes"]])
        ctc_w = np.array(c["tributary"])
        trib_rel = max(trib_rel, float(np.max(np.abs(w - ctc_w)) / np.max(np.abs(ctc_w))))
        alpha = c["stiffness"] * w if c["penalty_kind"] == "area" else np.full(len(w), c["stiffness"])
        contacts.append((c, np.array(c["nodes"]), alpha))

    X = np.array(problem["nodes"], dtype=np.float64)
    constrained = np.zeros(2 * n_nodes, dtype=bool)
    for d in problem["dirichlet"]:
        constrained[2 * np.array(d["nodes"]) + d["component"]] = True
    free = np.flatnonzero(~constrained)

    def contact_terms(u_ctc, k):
        """Nodal contact forces (ctc dof order) and tangent triplets."""
        f = np.zeros(2 * n_nodes)
        rows, cols, vals = [], [], []
        per_pair = []
        for c, nodes, alpha in contacts:
            tr = np.array(c["translation"][k])
            xn = X[nodes] + u_ctc.reshape(-1, 2)[nodes]
            forces = np.zeros((len(nodes), 2))
            for j, node in enumerate(nodes):
                if c["tool"] == "circle":
                    d = xn[j] - (np.array(c["point"]) + tr)
                    dist = np.linalg.norm(d)
                    g = dist - c["radius"]
                    nrm = d / dist
                    hess = (np.eye(2) - np.outer(nrm, nrm)) / dist
                else:
                    nrm = np.array(c["normal"])
                    g = float(np.dot(xn[j] - (np.array(c["point"]) + tr), nrm))
                    hess = np.zeros((2, 2))
                if g >= 0.0:
                    continue
                fj = -alpha[j] * g * nrm
                kj = alpha[j] * (np.outer(nrm, nrm) + g * hess)
                forces[j] = fj
                f[2 * node : 2 * node + 2] += fj
                for a in range(2):
                    for b in range(2):
                        rows.append(2 * node + a)
                        cols.append(2 * node + b)
                        vals.append(kj[a, b])
            per_pair.append(forces)
        kc = scipy.sparse.csr_matrix((vals, (rows, cols)), shape=(2 * n_nodes, 2 * n_nodes))
        return f, kc, per_pair

    # Permutation matrix DOLFINx dof -> ctc dof.
    perm = scipy.sparse.csr_matrix(
        (np.ones(2 * n_nodes), (np.arange(2 * n_nodes), dof)), shape=(2 * n_nodes, n_dofs)
    )
    u_ctc = np.zeros(2 * n_nodes)
    iterations = []
    residuals = []
    t_newton = time.perf_counter()
    tol = problem["newton_tol"]
    max_iter = problem["newton_max_iter"]
    per_pair = [np.zeros((len(c["nodes"]), 2)) for c in problem["contacts"]]
    for k, _t in enumerate(problem["times"]):
        f_ext = np.zeros(2 * n_nodes)
        for i, p in enumerate(problem["pressure"]):
            f_ext += p["values"][k] * (perm @ unit_pressure[i])
        for d in problem["dirichlet"]:
            u_ctc[2 * np.array(d["nodes"]) + d["component"]] = d["values"][k]
        count = 0
        history = []
        while True:
            u.x.array[dof] = u_ctc
            u.x.scatter_forward()
            f_int = perm @ assemble_vec(f_int_form)
            f_c, kc, per_pair = contact_terms(u_ctc, k)
            r = f_int - f_ext - f_c
            reactions = np.where(constrained, r, 0.0)
            ref = max(np.linalg.norm(f_ext + f_c) + np.linalg.norm(reactions), np.linalg.norm(f_int), 1e-300)
            rel = np.linalg.norm(r[free]) / ref
            if count > 0:
                history.append(float(rel))
            if count > 0 and rel <= tol:
                break
            if count >= max_iter:
                raise RuntimeError(f"increment {k + 1}: no convergence in {max_iter} iterations (rel {rel:.3e})")
            a = dolfinx.fem.petsc.assemble_matrix(jac_form)
            a.assemble()
            K = perm @ petsc_to_scipy(a) @ perm.T + kc
            a.destroy()
            Kff = K[free][:, free].tocsc()
            u_ctc[free] += scipy.sparse.linalg.spsolve(Kff, -r[free])
            count += 1
        iterations.append(count)
        residuals.append(history)
    end = time.perf_counter()
    return {
        "case": problem["case"],
        "dolfinx_version": dolfinx.__version__,
        "displacement": u_ctc.reshape(-1, 2).tolist(),
        "contact_forces": [f.tolist() for f in per_pair],
        "total_contact_force": [f.sum(axis=0).tolist() for f in per_pair],
        "newton_iterations": iterations,
        "residuals": residuals,
        "wall_time": end - t_newton,
        "setup_time": t_newton - t_start,
        "tributary_max_rel_diff": trib_rel,
    }


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: solve.py PROBLEM.json OUT.json")
    with open(sys.argv[1]) as fh:
        problem = json.load(fh)
    if problem.get("format") != "ctc-fenicsx-problem-1":
        sys.exit(f"{sys.argv[1]}: unknown format {problem.get('format')!r}")
    result = solve(problem)
    with open(sys.argv[2], "w") as fh:
        json.dump(result, fh, separators=(",", ":"))
        fh.write("\n")
    print(
        f"{result['case']}: {len(problem['nodes'])} nodes, Newton {result['newton_iterations']}, "
        f"{result['wall_time']:.3f} s (+ setup {result['setup_time']:.3f} s), tributary diff {result['tributary_max_rel_diff']:.1e}, "
        f"total contact force {result['total_contact_force']}"
    )


if __name__ == "__main__":
    main()
