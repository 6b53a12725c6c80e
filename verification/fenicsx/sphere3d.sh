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
# shellcheck source=side_by_side.sh
. "$HERE/side_by_side.sh"
# CTC_BIN: an already built ctc (skips the release build)
side_by_side_setup "sphere3d_$N"
"$PY" "$HERE/sphere3d.py" "$OUT" --n "$N" --export-only

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

side_by_side_table "3D Hertz sphere: ctc vs DOLFINx 0.11 ($(date -u +%Y-%m-%dT%H:%MZ), $(nproc --all) cores, reps $REPS, N $N)" \
  "$PY" "$HERE/sphere3d.py" --table "$OUT"
