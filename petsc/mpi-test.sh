#!/usr/bin/env bash
# Builds the MPI tests of ctc-petsc (feature `petsc`) and runs them on N
# ranks (default 2): the distributed elasticity solves, and the engine's
# Newton loop on PetscSystem for a finite-strain plastic strip (each rank
# its cells' integration points, exchanged at each commit) against the
# serial run:
#   bash petsc/mpi-test.sh 2
set -euo pipefail
cd "$(dirname "$0")/.."
ranks="${1:-2}"
# `-p ctc -p ctc-petsc --features ctc/petsc`: the feature resolution every
# PETSc command of `.ci/run` uses, so this build reuses theirs (with
# `-p ctc-petsc` alone nalgebra, faer and the engine resolve differently and
# are compiled once more).
exe=$(cargo test -p ctc -p ctc-petsc --features ctc/petsc --test mpi_elasticity --no-run \
        --message-format=json 2>/dev/null |
      sed -n 's/.*"name":"mpi_elasticity".*"executable":"\([^"]*\)".*/\1/p' | tail -1)
if [ -z "$exe" ]; then
  echo "could not build the mpi_elasticity test" >&2
  exit 1
fi
mpirun --allow-run-as-root --oversubscribe -n "$ranks" "$exe"
