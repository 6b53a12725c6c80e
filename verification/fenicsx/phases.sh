#!/usr/bin/env bash
# Per-phase times of ctc on the tutorial-style Hertz deck (issue 20), for
# several binaries and thread counts, alternating, REPS times each; the
# load average is logged before each run; the table gives, per variant,
# the min over the runs of the loop time (engine total less output), the
# process CPU (user + sys), and each phase of that fastest run; the
# results of every run are compared with the first one's (contact CSVs
# and history, byte for byte).
#
# Usage: bash verification/fenicsx/phases.sh REPS LABEL=BIN:THREADS ...
#   e.g. bash verification/fenicsx/phases.sh 3 before=target/ctc-before:1 \
#          after=target/release/ctc:1 after=target/release/ctc:2
# Needs target/speed/tutorial/tutorial.ctc (written by tutorial.sh, or
# `tutorial.py DIR --export-only`). Output: target/speed/phases/.
set -euo pipefail
REPS=${1:?REPS}
shift
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
DECK="$ROOT/target/speed/tutorial/tutorial.ctc"
OUT="$ROOT/target/speed/phases"
test -s "$DECK" || { echo "no $DECK: run tutorial.sh (or tutorial.py --export-only) first" >&2; exit 1; }
rm -rf "$OUT"
mkdir -p "$OUT"
for rep in $(seq 1 "$REPS"); do
  i=0
  for v in "$@"; do
    i=$((i + 1))
    label=${v%%=*}
    spec=${v#*=}
    bin=${spec%:*}
    threads=${spec##*:}
    dir="$OUT/$i-$label-t$threads-$rep"
    echo "$(date -u +%H:%M:%S) $label t$threads rep $rep: $(cut -d' ' -f1-3 /proc/loadavg)" >>"$OUT/load.txt"
    mkdir -p "$dir"
    /usr/bin/time -f "%U %S" -o "$dir/cpu.txt" "$bin" run "$DECK" -q -o "$dir" --threads "$threads"
  done
done
python3 - "$OUT" <<'EOF'
import glob, json, os, sys
out = sys.argv[1]
runs = {}
for d in sorted(glob.glob(os.path.join(out, "*-t*-*"))):
    key = os.path.basename(d).rsplit("-", 1)[0]
    s = json.load(open(os.path.join(d, "summary.json")))
    u, sy = (float(x) for x in open(os.path.join(d, "cpu.txt")).read().split()[:2])
    t = s["timings"]
    runs.setdefault(key, []).append((t["total"] - t["output"], u + sy, s, d))
ref = None
same = []
for key, rs in runs.items():
    for _, _, _, d in rs:
        files = sorted(os.path.basename(f) for f in glob.glob(os.path.join(d, "contact_0_*.csv"))) + ["history.csv"]
        data = [open(os.path.join(d, f), "rb").read() for f in files]
        ref = ref or data
        same.append(data == ref)
phases = ["setup", "assembly", "contact", "factorization", "symbolic", "low_rank", "solve", "residual"]
print("| variant | Newton its | loop wall, min [s] | all runs [s] | CPU, min [s] | " + " | ".join(phases) + " | other | output |")
print("|---|---|---|---|---|" + "---|" * (len(phases) + 2))
for key, rs in runs.items():
    best = min(rs, key=lambda r: r[0])
    t = best[2]["timings"]
    other = t["total"] - t["output"] - sum(t[p] for p in phases if p not in ("symbolic", "low_rank"))
    print(f"| {key.split('-', 1)[1]} | {best[2]['newton_iterations']} | {best[0]:.3f} | "
          + " ".join(f"{r[0]:.3f}" for r in rs) + f" | {min(r[1] for r in rs):.3f} | "
          + " | ".join(f"{1e3 * t[p]:.0f}" for p in phases) + f" | {1e3 * other:.0f} | {1e3 * t['output']:.0f} |")
print()
print("phases in ms of the fastest run; symbolic and low_rank are parts of factorization; "
      f"results identical to the first run's in {sum(same)} of {len(same)} runs (contact CSVs, history.csv)")
EOF
echo
echo "load average (1, 5, 15 min) before each run:"
cat "$OUT/load.txt"
