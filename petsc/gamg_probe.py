#!/usr/bin/python3
"""Replays one linear solve of a `ctc run --solver petsc` (1 rank) in petsc4py
to study the CG + GAMG preconditioner away from the Newton loop.

1. Dump the matrices and right-hand sides of every solve of the run (PETSc's own
   viewers, appended):
     CTC_EXE=target/debug/ctc bash petsc/large_contact.sh 15 1 OUT -- \
       -ksp_view_mat binary:OUT/mat.bin::append -ksp_view_rhs binary:OUT/rhs.bin::append
2. The node coordinates (natural order = PETSc order on 1 rank), for the
   rigid-body near-null space ctc gives GAMG (needs meshio):
     python3 petsc/vtu_coords.py OUT/run/inc_0001_p0.vtu OUT/x.npy
3. Replay solve INDEX (0-based, in the order of the run) with any PETSc options
   (needs the Debian python3-petsc4py, scipy for -probe_levels: `bash
   petsc/install.sh --probe` installs them):
     /usr/bin/python3 petsc/gamg_probe.py OUT/mat.bin OUT/x.npy INDEX [options]
   -probe_symmetry      ||A - A^T||_F / ||A||_F and MatIsSymmetric(1e-10)
   -probe_random N      N more solves with random right-hand sides (-probe_seed S)
   -probe_levels        per multigrid level below 500k rows: the true largest
                        eigenvalue of D^-1 A (scipy eigsh; zero diagonals taken
                        as 1, as PCJACOBI does) to compare with GAMG's estimate
                        (-info :pc prints it), and the zero rows of the level
                        (singleton aggregates: 6 modes on 3 dofs)
The replay of ctc's own solve gives ctc's Krylov count to +-1 (the
coordinates come from the VTU, which ctc writes in the reference
configuration or not: the modes may differ in the last digits).
"""
import os
import sys
import time

import petsc4py

petsc4py.init([sys.argv[0]] + sys.argv[4:])
from petsc4py import PETSc  # noqa: E402
import numpy as np  # noqa: E402

matfile, coordfile, index = sys.argv[1], sys.argv[2], int(sys.argv[3])
viewer = PETSc.Viewer().createBinary(matfile, "r")
for i in range(index + 1):
    A = PETSc.Mat().load(viewer)
    if i < index:
        A.destroy()
b = None
# the right-hand sides beside the matrices: mat.bin -> rhs.bin
head, tail = os.path.split(matfile)
rhsfile = os.path.join(head, tail.replace("mat", "rhs", 1))
try:
    vb = PETSc.Viewer().createBinary(rhsfile, "r")
    for i in range(index + 1):
        b = PETSc.Vec().load(vb)
except PETSc.Error as e:
    print("no right-hand side file, a random one:", e)
n = A.getSize()[0]
X = np.load(coordfile)
assert X.shape[0] * 3 == n, (X.shape, n)
# the rigid-body modes as petsc/src/nullspace.rs builds them: translations,
# rotations about the centroid, orthonormalised by two Gram-Schmidt passes
x = X - X.mean(axis=0)
modes = []
for k in range(6):
    m = np.zeros((X.shape[0], 3))
    if k < 3:
        m[:, k] = 1
    elif k == 3:
        m[:, 1], m[:, 2] = -x[:, 2], x[:, 1]
    elif k == 4:
        m[:, 0], m[:, 2] = x[:, 2], -x[:, 0]
    else:
        m[:, 0], m[:, 1] = -x[:, 1], x[:, 0]
    modes.append(m.ravel())
vecs = []
for m in modes:
    w = A.createVecLeft()
    w.setArray(m)
    vecs.append(w)
for _ in range(2):
    for i in range(6):
        for j in range(i):
            vecs[i].axpy(-vecs[i].dot(vecs[j]), vecs[j])
        vecs[i].normalize()
A.setNearNullSpace(PETSc.NullSpace().create(vectors=vecs))
opts = PETSc.Options()
if opts.getBool("probe_symmetry", False):
    At = A.transpose(PETSc.Mat())
    At.axpy(-1.0, A)
    nf = PETSc.NormType.FROBENIUS
    print("||A - A^T||_F / ||A||_F =", At.norm(nf) / A.norm(nf))
    print("MatIsSymmetric(1e-10) =", A.isSymmetric(1e-10))
A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
if b is None:
    b = A.createVecLeft()
    b.setRandom()
ksp = PETSc.KSP().create()
ksp.setOperators(A)
ksp.setType("cg")
ksp.getPC().setType("gamg")
ksp.setTolerances(rtol=1e-10, atol=1e-300, max_it=10000)
ksp.setFromOptions()
xs = A.createVecRight()
t0 = time.process_time()
ksp.setUp()
t1 = time.process_time()
ksp.solve(b, xs)
t2 = time.process_time()
print(
    f"index {index}: {ksp.getIterationNumber()} its, reason {ksp.getConvergedReason()}, "
    f"setup {t1 - t0:.2f} s, solve {t2 - t1:.2f} s (CPU)"
)
rnd = PETSc.Random().create()
rnd.setSeed(opts.getInt("probe_seed", 1))
for k in range(opts.getInt("probe_random", 0)):
    b.setRandom(rnd)
    t1 = time.process_time()
    ksp.solve(b, xs)
    print(
        f"random rhs {k}: {ksp.getIterationNumber()} its, reason "
        f"{ksp.getConvergedReason()}, solve {time.process_time() - t1:.2f} s"
    )
if opts.getBool("probe_levels", False):
    import scipy.sparse as sp
    import scipy.sparse.linalg as sla

    pc = ksp.getPC()
    for level in range(1, pc.getMGLevels()):
        smoother = pc.getMGSmoother(level)
        Al, _ = smoother.getOperators()
        m = Al.getSize()[0]
        if m > 500000:
            continue
        ia, ja, a = Al.getValuesCSR()
        M = sp.csr_matrix((a, ja, ia), shape=(m, m))
        d = M.diagonal()
        s = sp.diags(1 / np.sqrt(np.where(d == 0, 1.0, np.abs(d))))
        S = s @ M @ s
        top = max(sla.eigsh(S, k=2, which="LA", tol=1e-5, return_eigenvectors=False))
        zero_rows = int(sum(1 for i in range(m) if not np.any(M.data[M.indptr[i]:M.indptr[i + 1]])))
        print(
            f"level {level} (N={m}): largest eigenvalue of D^-1 A {top:.5f}; zero rows "
            f"{zero_rows}, negative diagonal entries {(d < 0).sum()}; smoother "
            f"{smoother.getType()} / {smoother.getPC().getType()}"
        )
