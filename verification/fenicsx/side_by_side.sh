# Shared parts of the side-by-side scripts (tutorial.sh, sphere3d.sh,
# neo_indent.sh, speed.sh): sourced after `HERE` (this directory) is set.

# side_by_side_setup NAME: ROOT (the repository), OUT (target/speed/NAME,
# created, its earlier runs removed), PY (the DOLFINx 0.11 python of
# install-0.11.sh, installed if missing) and CTC (CTC_BIN, an already built
# ctc, or a release build); one thread everywhere; cd to ROOT.
side_by_side_setup() {
  ROOT=$(cd "$HERE/../.." && pwd)
  OUT="$ROOT/target/speed/$1"
  export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
  bash "$HERE/install-0.11.sh" >/dev/null
  PY=$(bash "$HERE/install-0.11.sh" --python)
  mkdir -p "$OUT"
  rm -rf "$OUT"/ctc_* "$OUT"/fx_* "$OUT"/load.txt
  cd "$ROOT"
  if [ -z "${CTC_BIN:-}" ]; then cargo build --release -q -p ctc --bin ctc; fi
  CTC=${CTC_BIN:-$ROOT/target/release/ctc}
}

# load LABEL: appends the time and the load average to $OUT/load.txt.
load() { echo "$(date -u +%H:%M:%S) $1: $(cut -d' ' -f1-3 /proc/loadavg)" >>"$OUT/load.txt"; }

# side_by_side_table TITLE COMMAND...: prints (and writes to
# $OUT/table.md) the title, the output of COMMAND (the script's table) and
# the load log.
side_by_side_table() {
  local title=$1
  shift
  {
    echo "## $title"
    echo
    "$@"
    echo
    echo "Load average (1, 5, 15 min) around each run:"
    echo
    echo '```text'
    cat "$OUT/load.txt"
    echo '```'
  } | tee "$OUT/table.md"
}
