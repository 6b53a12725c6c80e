#!/usr/bin/env python3
"""Times sparse direct factorizations of the tangent ctc exported (issue 20).

    ctc run tutorial.ctc -q -o out --export-matrix K.mtx     # writes K.mtx, K.mtx.json
    PY=$(bash verification/fenicsx/install-0.11.sh --python)
    OMP_NUM_THREADS=1 $PY verification/fenicsx/factor_compare.py K.mtx [--reps 3] [--install]

`K.mtx` is the first tangent of the run (free dofs, Matrix Market,
symmetric); `K.mtx.json` holds ctc's time for its first factorization of
that matrix (faer: symbolic analysis with AMD and nested dissection, the
smaller factor kept, then the numeric L L^T or L D L^T; a Cholesky attempt
that broke down on an indefinite tangent is in the numeric time).

Timed here on the same matrix, min of `--reps`, single-threaded:
- SciPy SuperLU (`splu`, `MMD_AT_PLUS_A` ordering: symmetric pattern);
- CHOLMOD through scikit-sparse (`--install`: pip-installs scikit-sparse
  0.4.13 into this Python first, built against Debian's libsuitesparse-dev
  5.12: later versions need SuiteSparse 7), an
  L D L^T (`mode="simplicial"` and `"supernodal"`, the tangent may be
  indefinite);
- MUMPS through petsc4py (the DOLFINx 0.11 venv's PETSc): LU and symmetric
  L D L^T (`cholesky`, SYM = 2), with the ordering MUMPS reports using
  (INFOG(7): 5 = METIS, 7 = automatic choice; METIS is asked for with
  ICNTL(7) = 5 when PETSc's MUMPS has it).
Each solver's time is the symbolic analysis plus the numeric factorization
(a new factorization object per repetition); the first numeric
factorization alone is given where the solver separates it. The table goes
to stdout (Markdown) and `K.mtx.compare.json`.
"""

import argparse
import json
import subprocess
import sys
import time

PETSc, PETSC_ERROR = None, "not imported"
if sys.argv[-2:] == ["--solver", "mumps"]:
    try:  # the DOLFINx wheel's shared libraries (MPI, PETSc with MUMPS, its
        # BLAS) before SciPy's; SciPy's solvers run in another process
        import dolfinx_solver  # noqa: F401
        from petsc4py import PETSc
    except ImportError as e:
        PETSC_ERROR = str(e)

import scipy.io  # noqa: E402
import scipy.sparse as sp  # noqa: E402
import scipy.sparse.linalg as spla  # noqa: E402


def best(f, reps):
    """Min wall time of `reps` calls of f (each returns its own split
    times as a dict, or None)."""
    runs = []
    for _ in range(reps):
        t0 = time.perf_counter()
        extra = f() or {}
        runs.append((time.perf_counter() - t0, extra))
    return min(runs, key=lambda r: r[0])


def scipy_splu(a, reps):
    csc = a.tocsc()
    t, _ = best(lambda: spla.splu(csc, permc_spec="MMD_AT_PLUS_A"), reps)
    lu = spla.splu(csc, permc_spec="MMD_AT_PLUS_A")
    return {"solver": f"SciPy {scipy.__version__} SuperLU (MMD_AT_PLUS_A)", "total": t,
            "factor_nonzeros": int(lu.L.nnz + lu.U.nnz)}


def cholmod(a, reps, install):
    try:
        from sksparse import cholmod as cm
    except ImportError:
        if not install:
            return [{"solver": "CHOLMOD (scikit-sparse)", "error": "not installed (use --install)"}]
        r = subprocess.run([sys.executable, "-m", "pip", "install", "-q", "scikit-sparse==0.4.13"],
                           capture_output=True, text=True)
        try:
            from sksparse import cholmod as cm
        except ImportError:
            return [{"solver": "CHOLMOD (scikit-sparse)",
                     "error": "pip install scikit-sparse failed: " + (r.stderr.strip().splitlines() or ["?"])[-1]}]
    out = []
    csc = a.tocsc()
    for mode in ("supernodal", "simplicial"):
        try:
            def once():
                t0 = time.perf_counter()
                f = cm.analyze(csc, mode=mode)
                t1 = time.perf_counter()
                f.cholesky_inplace(csc)
                return {"symbolic": t1 - t0}
            t, extra = best(once, reps)
            out.append({"solver": f"CHOLMOD {mode} (scikit-sparse)", "total": t, **extra})
        except Exception as e:  # an indefinite tangent: CHOLMOD's LL^T refuses it
            out.append({"solver": f"CHOLMOD {mode} (scikit-sparse)", "error": str(e).splitlines()[0]})
    return out


def mumps(a, reps):
    if PETSc is None:
        return [{"solver": "MUMPS (petsc4py)", "error": f"petsc4py not available: {PETSC_ERROR}"}]
    csr = a.tocsr()
    out = []
    for factor in ("lu", "cholesky"):
        for icntl7 in (None, 5):
            def once():
                A = PETSc.Mat().createAIJ(size=csr.shape, csr=(csr.indptr.astype(PETSc.IntType),
                                                               csr.indices.astype(PETSc.IntType),
                                                               csr.data))
                A.assemble()
                if factor == "cholesky":
                    A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
                ksp = PETSc.KSP().create(PETSc.COMM_SELF)
                ksp.setOperators(A)
                ksp.setType("preonly")
                pc = ksp.getPC()
                pc.setType(factor)
                pc.setFactorSolverType("mumps")
                pc.setFactorSetUpSolverType()
                F = pc.getFactorMatrix()
                if icntl7 is not None:
                    F.setMumpsIcntl(7, icntl7)
                t0 = time.perf_counter()
                pc.setUp()
                t = time.perf_counter() - t0
                return {"setup": t, "ordering": int(F.getMumpsInfog(7)),
                        "factor_entries": int(F.getMumpsInfog(29))}
            try:
                t, extra = best(once, reps)
                # the PC set-up (analysis + factorization), not the matrix copy
                name = f"MUMPS {factor.upper() if factor == 'lu' else 'LDL^T'} (PETSc {'.'.join(map(str, PETSc.Sys.getVersion()))}, ICNTL(7) = {icntl7 if icntl7 is not None else 'default'})"
                out.append({"solver": name, "total": extra["setup"], **extra})
            except Exception as e:
                out.append({"solver": f"MUMPS {factor}", "error": str(e).splitlines()[0]})
    return out


ORDERINGS = {0: "AMD", 1: "user", 2: "AMF", 3: "SCOTCH", 4: "PORD", 5: "METIS", 6: "QAMD", 7: "auto"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("matrix")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--install", action="store_true")
    ap.add_argument("--solver", choices=["scipy", "mumps"], help="one family only, JSON out (internal)")
    args = ap.parse_args()
    import warnings
    warnings.simplefilter("ignore")
    t0 = time.perf_counter()
    a = sp.csr_matrix(scipy.io.mmread(args.matrix))
    read = time.perf_counter() - t0
    if args.solver == "scipy":
        print(json.dumps([scipy_splu(a, args.reps)] + cholmod(a, args.reps, args.install)))
        return
    if args.solver == "mumps":
        print(json.dumps(mumps(a, args.reps)))
        return
    with open(args.matrix + ".json") as f:
        ctc = json.load(f)
    n, nnz = a.shape[0], a.nnz
    rows = [{"solver": f"ctc (faer, {ctc['method']}, symbolic {1e3 * ctc['symbolic_seconds']:.0f} ms)",
             "total": ctc["first_factorization_seconds"], "factor_nonzeros": ctc["factor_nonzeros"]}]
    # each family in its own process: the DOLFINx wheel's BLAS and SciPy's
    # do not mix in one
    for family in ("scipy", "mumps"):
        cmd = [sys.executable, __file__, args.matrix, "--reps", str(args.reps)]
        if args.install:
            cmd.append("--install")
        r = subprocess.run(cmd + ["--solver", family], capture_output=True, text=True)
        try:
            rows += json.loads(r.stdout.strip().splitlines()[-1])
        except (IndexError, ValueError):
            tail = " ".join(r.stderr.strip().splitlines()[-2:])
            rows.append({"solver": family, "error": f"exit {r.returncode}: {tail}"})
    base = rows[0]["total"]
    print(f"## Factorization of ctc's first tangent ({n} rows, {nnz} stored entries, read in {read:.1f} s; min of {args.reps})")
    print()
    print("| solver | analysis + factorization [s] | / ctc | notes |")
    print("|---|---|---|---|")
    for r in rows:
        if "error" in r:
            print(f"| {r['solver']} | - | - | {r['error']} |")
            continue
        notes = []
        if "ordering" in r:
            notes.append(f"ordering used: {ORDERINGS.get(r['ordering'], r['ordering'])}")
        if "factor_entries" in r:
            notes.append(f"factor entries {r['factor_entries']}")
        if "factor_nonzeros" in r:
            notes.append(f"factor nonzeros {r['factor_nonzeros']}")
        if "symbolic" in r:
            notes.append(f"analysis {r['symbolic']:.3f} s")
        print(f"| {r['solver']} | {r['total']:.3f} | {r['total'] / base:.2f} | {'; '.join(notes)} |")
    with open(args.matrix + ".compare.json", "w") as f:
        json.dump({"rows": n, "nonzeros": nnz, "results": rows}, f, indent=1)


if __name__ == "__main__":
    main()
