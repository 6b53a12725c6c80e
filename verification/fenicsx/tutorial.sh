#!/usr/bin/env bash
# Side-by-side run of the tutorial-style 2D Hertz problem of issue 20:
# DOLFINx 0.11 (tutorial.py: SNES newtonls basic, rtol = atol = 1e-10,
# MUMPS LU) against ctc on the same mesh (exported by tutorial.py as gmsh)
# with the parabola as an exact quadratic NURBS (see SPEED.md).
#
# Runs, ALTERNATING, REPS times each: `ctc run tutorial.ctc` (release
# build) and `tutorial.py` under the DOLFINx 0.11 venv (install-0.11.sh);
# logs /proc/loadavg before and after each run; prints the min-of-REPS
# table (tutorial.py --table). Single-threaded everywhere.
#
# Usage: bash verification/fenicsx/tutorial.sh [REPS]   (from anywhere;
#        CTC_BIN=path/to/ctc to use a built binary)
# Output: target/speed/tutorial/ (ctc_<rep>/, fx_<rep>/, load.txt, table.md)
set -euo pipefail
REPS=${1:-3}
HERE=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=side_by_side.sh
. "$HERE/side_by_side.sh"
# CTC_BIN: an already built ctc (skips the release build)
side_by_side_setup "tutorial"
"$PY" "$HERE/tutorial.py" "$OUT" --export-only 2>/dev/null

for rep in $(seq 1 "$REPS"); do
  load "before ctc $rep"
  mkdir -p "$OUT/ctc_$rep"
  /usr/bin/time -f "%U %S" -o "$OUT/ctc_$rep/cpu.txt" "$CTC" run "$OUT/tutorial.ctc" -q -o "$OUT/ctc_$rep"
  load "after ctc $rep / before FEniCSx $rep"
  "$PY" "$HERE/tutorial.py" "$OUT/fx_$rep" 2>/dev/null | tail -n 1
  load "after FEniCSx $rep"
done

side_by_side_table "tutorial 2D Hertz: ctc vs DOLFINx 0.11 ($(date -u +%Y-%m-%dT%H:%MZ), $(nproc --all) cores, reps $REPS)" \
  "$PY" "$HERE/tutorial.py" --table "$OUT"
