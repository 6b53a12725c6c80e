#!/usr/bin/env bash
# Side-by-side run of the finite-strain Neo-Hooke indentation of issue 20
# (plane strain block, compressible Neo-Hooke, rigid circle R = 1 pressed to
# R/2, frictionless area penalty 10 E / h; see neo_indent.py and SPEED.md,
# section "Neo-Hooke indentation"): ctc against DOLFINx 0.11 on the same
# mesh (exported by neo_indent.py as gmsh), the same strain energy, circle,
# penalty and increments. DOLFINx runs twice per rep: contact integrated at
# the edge vertices (`vertex`, ctc's discrete problem exactly) and with
# Gauss degree 2 (`gauss`, the FEniCSx tutorials' style).
#
# Runs, ALTERNATING, REPS times each: `ctc run neo_indent.ctc` (release
# build) and `neo_indent.py --rule vertex|gauss` under the DOLFINx 0.11
# venv (install-0.11.sh), all under /usr/bin/time (process wall, user +
# sys CPU, peak RSS); logs /proc/loadavg before and after each run; prints
# the per-increment table (iterations, force) and the totals and walls
# (neo_indent.py --table). Single-threaded everywhere.
#
# Usage: bash verification/fenicsx/neo_indent.sh [REPS] [NX] [STEPS]
#        (from anywhere; NX cells across, NX / 2 down, default 24; STEPS
#        increments, default 10; CTC_BIN=path/to/ctc to use a built binary;
#        LINESEARCH=basic for DOLFINx without its default bt line search)
# Output: target/speed/neo_indent_<NX>/ (neo_indent.msh, neo_indent.ctc,
#         mesh.json, ctc_<rep>/, fx_vertex_<rep>/, fx_gauss_<rep>/,
#         load.txt, table.md)
set -euo pipefail
REPS=${1:-3}
NX=${2:-24}
STEPS=${3:-10}
NY=$((NX / 2))
LS=${LINESEARCH:-bt}
HERE=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=side_by_side.sh
. "$HERE/side_by_side.sh"
# CTC_BIN: an already built ctc (skips the release build)
side_by_side_setup "neo_indent_$NX"
"$PY" "$HERE/neo_indent.py" "$OUT" --nx "$NX" --ny "$NY" --steps "$STEPS" --export-only

for rep in $(seq 1 "$REPS"); do
  load "before ctc $rep"
  mkdir -p "$OUT/ctc_$rep"
  /usr/bin/time -f "%e %U %S %M" -o "$OUT/ctc_$rep/time.txt" \
    "$CTC" run "$OUT/neo_indent.ctc" -q -o "$OUT/ctc_$rep" --threads 1 || echo "ctc run $rep did not complete (see $OUT/ctc_$rep/summary.json)"
  for rule in vertex gauss; do
    load "before FEniCSx $rule $rep"
    mkdir -p "$OUT/fx_${rule}_$rep"
    /usr/bin/time -f "%e %U %S %M" -o "$OUT/fx_${rule}_$rep/time.txt" \
      "$PY" "$HERE/neo_indent.py" "$OUT/fx_${rule}_$rep" --nx "$NX" --ny "$NY" --steps "$STEPS" \
      --rule "$rule" --linesearch "$LS" 2>/dev/null | cut -c1-200 || echo "FEniCSx $rule run $rep failed"
  done
  load "after FEniCSx $rep"
done

side_by_side_table "Neo-Hooke indentation: ctc vs DOLFINx 0.11 ($(date -u +%Y-%m-%dT%H:%MZ), $(nproc --all) cores, reps $REPS, $NX x $NY cells, $STEPS increments, DOLFINx line search $LS)" \
  "$PY" "$HERE/neo_indent.py" --table "$OUT"
