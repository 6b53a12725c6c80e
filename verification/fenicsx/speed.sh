#!/usr/bin/env bash
# Speed and Newton-iteration comparison of `ctc bench` with FEniCSx on the
# same mesh and penalty (see SPEED.md).
#
# Exports the exact problem `ctc bench --size SIZE` solves (the
# `fenicsx_export --bench` example runs `run_bench` with `deck_out` and
# exports that deck), then runs, ALTERNATING, REPS times each:
#   ctc bench --size SIZE --json          (release build)
#   speed.py variant A (ctc's nodal penalty, PETSc assembly, MUMPS LU)
#   speed.py variant B (tutorial quadrature-point penalty, NewtonSolver, MUMPS LU)
# recording the load average before and after each run, and prints the
# min-of-REPS table (speed.py --table).
#
# Single-threaded everywhere (OMP/OpenBLAS threads = 1): ctc has no threads
# in numerics, and the machine is shared.
#
# Usage: bash verification/fenicsx/speed.sh SIZE [REPS]   (from anywhere)
# Output: target/speed/<SIZE>/ (run files, load.txt, table.md)
set -euo pipefail
SIZE=${1:?usage: speed.sh SIZE [REPS]}
REPS=${2:-3}
PY=${FENICSX_PYTHON:-/usr/bin/python3}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT="$ROOT/target/speed/$SIZE"
# shellcheck source=side_by_side.sh
. "$HERE/side_by_side.sh"
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
mkdir -p "$OUT"
rm -f "$OUT"/ctc_*.json "$OUT"/ctc_*.cpu "$OUT"/A_*.json "$OUT"/B_*.json "$OUT"/load.txt

cd "$ROOT"
# one cargo invocation for both (separate ones unify features differently
# and rebuild each other's dependencies)
cargo build --release -q -p ctc --bin ctc -p ctc-verification --example fenicsx_export
CTC="$ROOT/target/release/ctc"
"$ROOT/target/release/examples/fenicsx_export" --bench "$SIZE" "$OUT" >/dev/null
PROBLEM="$OUT/bench_$SIZE.problem.json"

for rep in $(seq 1 "$REPS"); do
  load "before ctc $rep"
  # CPU (user + sys) of the whole ctc process: an upper bound of its loop's
  /usr/bin/time -f "%U %S" -o "$OUT/ctc_$rep.cpu" "$CTC" bench --size "$SIZE" --json >"$OUT/ctc_$rep.json"
  load "after ctc $rep / before A $rep"
  "$PY" "$HERE/speed.py" "$PROBLEM" "$OUT/A_$rep.json" --variant A 2>/dev/null | tail -n 1
  load "after A $rep / before B $rep"
  "$PY" "$HERE/speed.py" "$PROBLEM" "$OUT/B_$rep.json" --variant B 2>/dev/null | tail -n 1
  load "after B $rep"
done

side_by_side_table "ctc bench --size $SIZE vs FEniCSx ($(date -u +%Y-%m-%dT%H:%MZ), $(nproc --all) cores, reps $REPS)" \
  "$PY" "$HERE/speed.py" --table "$OUT"
