#!/usr/bin/env bash
# Scaling of ctc with the problem size (issue 20, "Scaling: 2D Hertz from
# 10k to 1M dofs and 3D from 10k to the largest that fits: time and memory
# against dofs, with the fitted exponents"). See SPEED.md.
#
# 2D: `ctc bench --size S --json` (rigid cylinder on the graded block, 4
#     increments to d = 0.02, area penalty 10 E / h_min), S = 0.125 .. 12.5
#     (10,100 .. 1,001,000 free dofs).
# 3D: the Hertz sphere of sphere3d.py (quarter model, graded P1 tetrahedra,
#     exact rigid sphere, 4 increments), N cubes per direction (N = 14:
#     ~9k free dofs; N = 40: 198,440); the mesh exported with numpy only.
# Every run under /usr/bin/time (process wall, user + sys CPU, peak RSS),
# single-threaded (CTC_THREADS, default 1), one after the other; the load
# average is logged around each run. scaling.py fits time and memory
# against free dofs (least squares in log-log) and writes table.md.
#
# Usage: bash verification/fenicsx/scaling.sh     (from anywhere)
#        SIZES_2D="0.125 1" N_3D="14 20" bash verification/fenicsx/scaling.sh
#        CTC_BIN=path/to/ctc to use a built binary (else a release build)
# Output: target/speed/scaling/ (2d_<S>/, 3d_<N>/, load.txt, table.md)
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT="$ROOT/target/speed/scaling"
SIZES_2D=${SIZES_2D:-"0.125 0.25 0.5 1 2 4 8 12.5"}
N_3D=${N_3D:-"14 20 25 30 35 40"}
THREADS=${CTC_THREADS:-1}
# numpy: Debian python3-numpy (the DOLFINx 0.5 install brings it) or any PYTHON with it
PY=${PYTHON:-/usr/bin/python3}
if [ -z "${CTC_BIN:-}" ]; then cargo build --release -q -p ctc --bin ctc; fi
CTC=${CTC_BIN:-$ROOT/target/release/ctc}
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
mkdir -p "$OUT"
load() { echo "$(date -u +%H:%M:%S) $1: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$OUT/load.txt"; }

for s in $SIZES_2D; do
  d="$OUT/2d_$s"
  mkdir -p "$d"
  load "before 2D $s"
  /usr/bin/time -f "%e %U %S %M" -o "$d/time.txt" \
    "$CTC" bench --size "$s" --json --threads "$THREADS" > "$d/bench.json"
  load "after 2D $s"
done

for n in $N_3D; do
  d="$OUT/3d_$n"
  mkdir -p "$d"
  "$PY" "$HERE/sphere3d.py" "$d" --n "$n" --export-only > /dev/null
  load "before 3D $n"
  /usr/bin/time -f "%e %U %S %M" -o "$d/time.txt" \
    "$CTC" run "$d/sphere3d.ctc" -q -o "$d/run" --threads "$THREADS"
  load "after 3D $n"
done

"$PY" "$HERE/scaling.py" "$OUT" | tee "$OUT/table.md"
