#!/usr/bin/env bash
# Side-by-side run of the 3D Hertz sphere of issue 20 (quarter model,
# graded P1 tetrahedra, exact rigid sphere, penalty 10 E / h_min on the top
# face): DOLFINx 0.11 (sphere3d.py: SNES newtonls basic, rtol = atol =
# 1e-10, MUMPS LU) against ctc on the same mesh (exported by sphere3d.py as
# gmsh). See SPEED.md.
#
# Runs, ALTERNATING, REPS times each: `ctc run sphere3d.ctc` (release
# build) and `sphere3d.py` under the DOLFINx 0.11 venv (install-0.11.sh),
# both under /usr/bin/time (process wall, user + sys CPU, peak RSS); logs
# /proc/loadavg before and after each run; prints the table
# (sphere3d.py --table). Single-threaded everywhere (CTC_THREADS, default 1).
#
# Usage: bash verification/fenicsx/sphere3d.sh [REPS] [N]   (from anywhere;
#        N cubes per direction, default 40: 198,440 free dofs;
#        CTC_BIN=path/to/ctc to use a built binary)
# Output: target/speed/sphere3d_<N>/ (sphere3d.msh, sphere3d.ctc, ctc_<rep>/,
#         fx_<rep>/, load.txt, table.md)
set -euo pipefail
REPS=${1:-3}
N=${2:-40}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT="$ROOT/target/speed/sphere3d_$N"
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
bash "$HERE/install-0.11.sh" >/dev/null
PY=$(bash "$HERE/install-0.11.sh" --python)
mkdir -p "$OUT"
rm -rf "$OUT"/ctc_* "$OUT"/fx_* "$OUT"/load.txt
cd "$ROOT"
# CTC_BIN: an already built ctc (skips the release build)
if [ -z "${CTC_BIN:-}" ]; then cargo build --release -q -p ctc --bin ctc; fi
CTC=${CTC_BIN:-$ROOT/target/release/ctc}
"$PY" "$HERE/sphere3d.py" "$OUT" --n "$N" --export-only

load() { echo "$(date -u +%H:%M:%S) $1: $(cut -d' ' -f1-3 /proc/loadavg)" >>"$OUT/load.txt"; }
for rep in $(seq 1 "$REPS"); do
  load "before ctc $rep"
  mkdir -p "$OUT/ctc_$rep" "$OUT/fx_$rep"
  /usr/bin/time -f "%e %U %S %M" -o "$OUT/ctc_$rep/time.txt" \
    "$CTC" run "$OUT/sphere3d.ctc" -q -o "$OUT/ctc_$rep" --threads "${CTC_THREADS:-1}"
  load "after ctc $rep / before FEniCSx $rep"
  /usr/bin/time -f "%e %U %S %M" -o "$OUT/fx_$rep/time.txt" \
    "$PY" "$HERE/sphere3d.py" "$OUT/fx_$rep" --n "$N" 2>/dev/null | tail -n 1
  load "after FEniCSx $rep"
done

{
  echo "## 3D Hertz sphere: ctc vs DOLFINx 0.11 ($(date -u +%Y-%m-%dT%H:%MZ), $(nproc --all) cores, reps $REPS, N $N)"
  echo
  "$PY" "$HERE/sphere3d.py" --table "$OUT"
  echo
  echo "Load average (1, 5, 15 min) around each run:"
  echo
  echo '```text'
  cat "$OUT/load.txt"
  echo '```'
} | tee "$OUT/table.md"
