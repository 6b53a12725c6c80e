#!/usr/bin/env bash
# Builds the MPI tests of ctc-petsc (feature `petsc`) and runs them on N
# ranks (default 2):
#   bash petsc/mpi-test.sh 2
set -euo pipefail
cd "$(dirname "$0")/.."
ranks="${1:-2}"
exe=$(cargo test -p ctc-petsc --features petsc --test mpi_elasticity --no-run \
        --message-format=json 2>/dev/null |
      sed -n 's/.*"name":"mpi_elasticity".*"executable":"\([^"]*\)".*/\1/p' | tail -1)
if [ -z "$exe" ]; then
  echo "could not build the mpi_elasticity test" >&2
  exit 1
fi
mpirun --allow-run-as-root --oversubscribe -n "$ranks" "$exe"
